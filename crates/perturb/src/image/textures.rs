//! Private textures of the image corruptions that need more than the shared scratch: created
//! once in `build`, reused every frame.

use crate::perturbation::Kit;

/// A storage + sampled texture of `format`, `width`×`height`.
pub fn storage_texture(
    kit: &Kit,
    label: &str,
    format: wgpu::TextureFormat,
    width: u32,
    height: u32,
) -> wgpu::Texture {
    kit.ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

/// A frame-sized `Rgba32Float` texture for full-precision intermediate results.
pub fn float4_frame_texture(kit: &Kit, label: &str) -> wgpu::Texture {
    storage_texture(
        kit,
        label,
        wgpu::TextureFormat::Rgba32Float,
        kit.width,
        kit.height,
    )
}
