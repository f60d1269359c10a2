use rslam_core::{DepthImage, RgbImage};

use crate::GpuContext;

/// One frame on the GPU: sRGB-encoded colour and metric z-depth (0 = invalid). The renderer
/// writes both, perturbations transform them in place, the readback copies them out once.
pub struct FrameTextures {
    pub width: u32,
    pub height: u32,
    /// `Rgba8Unorm` holding sRGB-encoded values (storage-capable); render through
    /// [`FrameTextures::color_render_view`] so that shading happens in linear space.
    pub color: wgpu::Texture,
    /// `R32Float`, metres along the optical axis.
    pub depth: wgpu::Texture,
    /// `R32Uint`, which object each pixel sees (0 the static scene, k actor k); only on frames
    /// made [`FrameTextures::with_mask`], for scenes with actors.
    pub mask: Option<wgpu::Texture>,
    color_view: wgpu::TextureView,
    color_render_view: wgpu::TextureView,
    depth_view: wgpu::TextureView,
    mask_view: Option<wgpu::TextureView>,
}

impl FrameTextures {
    pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
    pub const COLOR_SRGB_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
    pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;
    pub const MASK_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

    pub fn new(ctx: &GpuContext, width: u32, height: u32) -> Self {
        Self::with_mask(ctx, width, height, false)
    }

    /// Frame textures with an instance mask when `with_mask`.
    pub fn with_mask(ctx: &GpuContext, width: u32, height: u32, with_mask: bool) -> Self {
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST;
        let make = |label, format, view_formats: &[wgpu::TextureFormat]| {
            ctx.texture_2d(label, format, (width, height), usage, view_formats)
        };
        let color = make(
            "frame colour",
            Self::COLOR_FORMAT,
            &[Self::COLOR_SRGB_FORMAT],
        );
        let depth = make("frame depth", Self::DEPTH_FORMAT, &[]);
        let mask = with_mask.then(|| make("frame mask", Self::MASK_FORMAT, &[]));
        Self {
            width,
            height,
            color_view: color.create_view(&Default::default()),
            color_render_view: color.create_view(&wgpu::TextureViewDescriptor {
                format: Some(Self::COLOR_SRGB_FORMAT),
                usage: Some(wgpu::TextureUsages::RENDER_ATTACHMENT),
                ..Default::default()
            }),
            depth_view: depth.create_view(&Default::default()),
            mask_view: mask.as_ref().map(|m| m.create_view(&Default::default())),
            color,
            depth,
            mask,
        }
    }

    /// The colour texture seen as sRGB: a render target that encodes linear shading to sRGB.
    pub fn color_render_view(&self) -> &wgpu::TextureView {
        &self.color_render_view
    }

    pub fn color_view(&self) -> &wgpu::TextureView {
        &self.color_view
    }

    pub fn depth_view(&self) -> &wgpu::TextureView {
        &self.depth_view
    }

    pub fn mask_view(&self) -> Option<&wgpu::TextureView> {
        self.mask_view.as_ref()
    }

    pub fn size(&self) -> wgpu::Extent3d {
        wgpu::Extent3d {
            width: self.width,
            height: self.height,
            depth_or_array_layers: 1,
        }
    }

    /// Uploads a frame held in memory (arrays from Python, the viewer's frames). Without depth
    /// the depth texture keeps whatever it held: image-only inputs run image corruptions only,
    /// which never read it. Frames decoded from disk go through [`crate::FrameUploads`] instead.
    pub fn upload(&self, ctx: &GpuContext, color: &RgbImage, depth: Option<&DepthImage>) {
        let layout = |bytes_per_pixel: u32| wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(self.width * bytes_per_pixel),
            rows_per_image: Some(self.height),
        };
        let rgba = color.to_rgba();
        ctx.queue
            .write_texture(self.color.as_image_copy(), &rgba, layout(4), self.size());
        if let Some(depth) = depth {
            ctx.queue.write_texture(
                self.depth.as_image_copy(),
                bytemuck::cast_slice(&depth.data),
                layout(4),
                self.size(),
            );
        }
    }
}
