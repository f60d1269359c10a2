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
    kit.ctx.storage_texture(label, format, (width, height))
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
