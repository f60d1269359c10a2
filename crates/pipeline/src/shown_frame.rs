//! One output frame kept on the GPU for display: the source frames it comes from, clean and
//! perturbed, and their depth colour-mapped. Nothing is read back; a window samples the textures
//! directly (the viewer registers [`ShownViews`] with its renderer).

use rslam_gpu::{read_texels, wgpu, FrameTextures, GpuContext};

use crate::depth_colormap::{DepthColormap, DepthRange};
use crate::PipelineError;

/// Which source frames an output frame shows: its colour's and its depth's (they differ under
/// `misalign`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShownSources {
    pub rgb: usize,
    pub depth: usize,
}

/// What a [`ShownFrame`] holds: its source frames, drawn from a pose of the caller's instead of
/// the path's for a free camera, from sources as they were at `generation`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Held {
    pub sources: ShownSources,
    pub pose: Option<rslam_core::Pose>,
    pub generation: u64,
}

/// Views for sampling, made once: colour seen as sRGB, depth as its Turbo colours (sRGB).
pub struct ShownViews {
    pub clean_color: wgpu::TextureView,
    pub perturbed_color: wgpu::TextureView,
    pub clean_depth: wgpu::TextureView,
    pub perturbed_depth: wgpu::TextureView,
}

/// What one pixel holds, clean and perturbed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelReadout {
    pub clean_rgb: [u8; 3],
    pub perturbed_rgb: [u8; 3],
    /// Metres; 0 = no depth.
    pub clean_depth: f32,
    pub perturbed_depth: f32,
}

/// The GPU side of the shown frame, allocated once per frame size.
pub struct ShownFrame {
    /// The colour's source frame, as drawn or uploaded and after the corruptions.
    pub(crate) clean: FrameTextures,
    pub(crate) perturbed: FrameTextures,
    /// The depth's source frame when it is another one (`misalign`).
    pub(crate) lagged_clean: FrameTextures,
    pub(crate) lagged_perturbed: FrameTextures,
    clean_depth_colors: wgpu::Texture,
    perturbed_depth_colors: wgpu::Texture,
    colormap: DepthColormap,
    views: ShownViews,
    /// What `clean` (and `lagged_clean`) hold; `None` once they must be redrawn.
    pub(crate) held: Option<Held>,
    with_depth: bool,
}

impl ShownFrame {
    pub fn new(ctx: &GpuContext, width: u32, height: u32) -> Result<Self, PipelineError> {
        let clean = FrameTextures::new(ctx, width, height);
        let perturbed = FrameTextures::new(ctx, width, height);
        let depth_colors = |label| {
            ctx.texture_2d(
                label,
                FrameTextures::COLOR_FORMAT,
                (width, height),
                wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                &[FrameTextures::COLOR_SRGB_FORMAT],
            )
        };
        let clean_depth_colors = depth_colors("shown clean depth colours");
        let perturbed_depth_colors = depth_colors("shown perturbed depth colours");
        let srgb = |t: &wgpu::Texture| {
            t.create_view(&wgpu::TextureViewDescriptor {
                format: Some(FrameTextures::COLOR_SRGB_FORMAT),
                usage: Some(wgpu::TextureUsages::TEXTURE_BINDING),
                ..Default::default()
            })
        };
        let views = ShownViews {
            clean_color: srgb(&clean.color),
            perturbed_color: srgb(&perturbed.color),
            clean_depth: srgb(&clean_depth_colors),
            perturbed_depth: srgb(&perturbed_depth_colors),
        };
        Ok(Self {
            lagged_clean: FrameTextures::new(ctx, width, height),
            lagged_perturbed: FrameTextures::new(ctx, width, height),
            clean,
            perturbed,
            clean_depth_colors,
            perturbed_depth_colors,
            colormap: DepthColormap::new(ctx)?,
            views,
            held: None,
            with_depth: true,
        })
    }

    pub fn size(&self) -> (u32, u32) {
        (self.clean.width, self.clean.height)
    }

    pub fn views(&self) -> &ShownViews {
        &self.views
    }

    /// Whether the shown frame has depth (image-only inputs have none).
    pub fn has_depth(&self) -> bool {
        self.with_depth
    }

    pub(crate) fn set_has_depth(&mut self, with_depth: bool) {
        self.with_depth = with_depth;
    }

    /// The source frames last shown, if any.
    pub fn sources(&self) -> Option<ShownSources> {
        self.held.map(|h| h.sources)
    }

    /// The textures holding the shown depth: the colour's frame or the lagged one.
    fn depth_frames(&self, sources: ShownSources) -> (&FrameTextures, &FrameTextures) {
        if sources.rgb == sources.depth {
            (&self.clean, &self.perturbed)
        } else {
            (&self.lagged_clean, &self.lagged_perturbed)
        }
    }

    /// Records the colour-mapping of the shown depth at `range`.
    pub(crate) fn encode_depth_colors(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        sources: ShownSources,
        range: DepthRange,
    ) {
        let (clean, perturbed) = self.depth_frames(sources);
        self.colormap.encode(
            ctx,
            encoder,
            &[
                (&clean.depth, &self.clean_depth_colors),
                (&perturbed.depth, &self.perturbed_depth_colors),
            ],
            range,
        );
    }

    /// Colour and depth at pixel (`x`, `y`) of the frame last shown (a one-pixel readback, for
    /// the readout under the cursor; not part of displaying).
    pub fn read_pixel(
        &self,
        ctx: &GpuContext,
        x: u32,
        y: u32,
    ) -> Result<Option<PixelReadout>, PipelineError> {
        let (width, height) = self.size();
        let Some(Held { sources, .. }) = self.held else {
            return Ok(None);
        };
        if x >= width || y >= height {
            return Ok(None);
        }
        let (clean_depth, perturbed_depth) = self.depth_frames(sources);
        let texels = read_texels(
            ctx,
            &[
                (&self.clean.color, x, y),
                (&self.perturbed.color, x, y),
                (&clean_depth.depth, x, y),
                (&perturbed_depth.depth, x, y),
            ],
        )?;
        let rgb = |t: [u8; 4]| [t[0], t[1], t[2]];
        let depth = |t: [u8; 4]| {
            if self.with_depth {
                f32::from_ne_bytes(t)
            } else {
                0.0
            }
        };
        Ok(Some(PixelReadout {
            clean_rgb: rgb(texels[0]),
            perturbed_rgb: rgb(texels[1]),
            clean_depth: depth(texels[2]),
            perturbed_depth: depth(texels[3]),
        }))
    }
}

/// Records a copy of `from`'s colour and depth into `to` (same size).
pub(crate) fn copy_frame(
    encoder: &mut wgpu::CommandEncoder,
    from: &FrameTextures,
    to: &FrameTextures,
) {
    for (a, b) in [(&from.color, &to.color), (&from.depth, &to.depth)] {
        encoder.copy_texture_to_texture(a.as_image_copy(), b.as_image_copy(), from.size());
    }
}

#[cfg(test)]
#[path = "shown_frame_tests.rs"]
mod tests;
