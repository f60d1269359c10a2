//! All scene textures in one `texture_2d_array`: every layer resized to one square size, with a
//! box-filtered mip chain so that distant repeating textures do not alias into noise.

use rslam_gpu::GpuContext;

use crate::{RenderError, Texture};

/// Largest layer edge; bigger textures are downsampled to it.
const MAX_LAYER_SIZE: u32 = 2048;

fn layer_size(textures: &[Texture]) -> u32 {
    let largest = textures
        .iter()
        .map(|t| t.width.max(t.height))
        .max()
        .unwrap_or(1);
    largest.next_power_of_two().clamp(1, MAX_LAYER_SIZE)
}

fn resized(texture: &Texture, size: u32) -> Vec<u8> {
    if texture.width == size && texture.height == size {
        return texture.rgba.clone();
    }
    let Some(image) =
        image::RgbaImage::from_raw(texture.width, texture.height, texture.rgba.clone())
    else {
        return vec![255; (size * size * 4) as usize];
    };
    image::imageops::resize(&image, size, size, image::imageops::FilterType::Triangle).into_raw()
}

/// 2×2 box average of an RGBA8 square image of edge `size` (even or 1).
fn half(rgba: &[u8], size: u32) -> Vec<u8> {
    let s = size as usize;
    let h = (s / 2).max(1);
    let mut out = vec![0u8; h * h * 4];
    for y in 0..h {
        for x in 0..h {
            for c in 0..4 {
                let at = |xx: usize, yy: usize| {
                    rgba[((yy.min(s - 1)) * s + xx.min(s - 1)) * 4 + c] as u32
                };
                let sum = at(2 * x, 2 * y)
                    + at(2 * x + 1, 2 * y)
                    + at(2 * x, 2 * y + 1)
                    + at(2 * x + 1, 2 * y + 1);
                out[(y * h + x) * 4 + c] = ((sum + 2) / 4) as u8;
            }
        }
    }
    out
}

pub fn upload(
    ctx: &GpuContext,
    scene_name: &str,
    textures: &[Texture],
) -> Result<wgpu::Texture, RenderError> {
    let limit = ctx.device.limits().max_texture_array_layers;
    if textures.len() as u64 > limit as u64 {
        return Err(RenderError::TooManyTextures {
            name: scene_name.to_string(),
            count: textures.len(),
            limit,
        });
    }
    let size = layer_size(textures);
    let mip_levels = size.ilog2() + 1;
    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("scene textures"),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: textures.len().max(1) as u32,
        },
        mip_level_count: mip_levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (layer, source) in textures.iter().enumerate() {
        let mut level_size = size;
        let mut pixels = resized(source, size);
        for level in 0..mip_levels {
            ctx.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &texture,
                    mip_level: level,
                    origin: wgpu::Origin3d {
                        x: 0,
                        y: 0,
                        z: layer as u32,
                    },
                    aspect: wgpu::TextureAspect::All,
                },
                &pixels,
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(level_size * 4),
                    rows_per_image: Some(level_size),
                },
                wgpu::Extent3d {
                    width: level_size,
                    height: level_size,
                    depth_or_array_layers: 1,
                },
            );
            if level + 1 < mip_levels {
                pixels = half(&pixels, level_size);
                level_size = (level_size / 2).max(1);
            }
        }
    }
    Ok(texture)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layer_size_is_the_largest_edge_as_power_of_two_capped() {
        let t = |w, h| Texture {
            width: w,
            height: h,
            rgba: vec![0; (w * h * 4) as usize],
        };
        assert_eq!(layer_size(&[Texture::white()]), 1);
        assert_eq!(layer_size(&[Texture::white(), t(300, 200)]), 512);
        assert_eq!(layer_size(&[t(8192, 10)]), MAX_LAYER_SIZE);
    }

    #[test]
    fn half_averages_2x2_blocks() {
        let rgba: Vec<u8> = [0u8, 100, 200, 44]
            .iter()
            .flat_map(|&v| [v, v, v, 255])
            .collect();
        assert_eq!(half(&rgba, 2), vec![86, 86, 86, 255]);
    }
}
