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
