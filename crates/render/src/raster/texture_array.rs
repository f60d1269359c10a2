//! All scene textures in one `texture_2d_array`: every layer resized to one square size, with a
//! mip chain box-filtered in linear light (as the sRGB sampler filters), so that distant repeating
//! textures do not alias into noise and do not darken with distance.

use rslam_gpu::GpuContext;

use crate::scene::srgb::{linear_to_srgb, srgb_to_linear};
use crate::{RenderError, Texture};

/// Largest layer edge; bigger textures are downsampled to it (or to the device's limit, if lower).
const MAX_LAYER_SIZE: u32 = 2048;

/// The largest edge of any texture as a power of two, capped at `max_size` (rounded down to a
/// power of two so every mip level halves exactly).
fn layer_size(textures: &[Texture], max_size: u32) -> u32 {
    let cap = 1 << max_size.max(1).ilog2();
    let largest = textures
        .iter()
        .map(|t| t.width.max(t.height))
        .max()
        .unwrap_or(1);
    largest.next_power_of_two().clamp(1, cap)
}

/// A texture whose pixel buffer does not match its size cannot be sampled: an error, never a
/// stand-in colour.
fn check(scene_name: &str, layer: usize, texture: &Texture) -> Result<(), RenderError> {
    let bad = |message: String| RenderError::BadTextureData {
        name: scene_name.to_string(),
        layer,
        message,
    };
    if texture.width == 0 || texture.height == 0 {
        return Err(bad(format!(
            "empty texture ({}×{})",
            texture.width, texture.height
        )));
    }
    let expected = texture.width as u64 * texture.height as u64 * 4;
    if texture.rgba.len() as u64 != expected {
        return Err(bad(format!(
            "{} bytes of RGBA for {}×{} texels (expected {expected})",
            texture.rgba.len(),
            texture.width,
            texture.height
        )));
    }
    Ok(())
}

/// Resamples a checked texture to `size`×`size`, filtering in linear light.
fn resized(texture: &Texture, size: u32) -> Vec<u8> {
    if texture.width == size && texture.height == size {
        return texture.rgba.clone();
    }
    let linear: Vec<f32> = texture
        .rgba
        .chunks_exact(4)
        .flat_map(|p| {
            let [r, g, b] = [p[0], p[1], p[2]].map(srgb_to_linear);
            [r, g, b, p[3] as f32 / 255.0]
        })
        .collect();
    let image = image::Rgba32FImage::from_raw(texture.width, texture.height, linear)
        .expect("check() verified the buffer size");
    image::imageops::resize(&image, size, size, image::imageops::FilterType::Triangle)
        .into_raw()
        .chunks_exact(4)
        .flat_map(|p| {
            let [r, g, b] = [p[0], p[1], p[2]].map(linear_to_srgb);
            [r, g, b, (p[3].clamp(0.0, 1.0) * 255.0).round() as u8]
        })
        .collect()
}

/// 2×2 box average in linear light of an sRGB RGBA8 square image of edge `size` (even or 1);
/// alpha is averaged as stored.
fn half(rgba: &[u8], size: u32) -> Vec<u8> {
    let s = size as usize;
    let h = (s / 2).max(1);
    let mut out = vec![0u8; h * h * 4];
    for y in 0..h {
        for x in 0..h {
            let at = |xx: usize, yy: usize, c: usize| {
                rgba[((yy.min(s - 1)) * s + xx.min(s - 1)) * 4 + c]
            };
            let quad = [
                (2 * x, 2 * y),
                (2 * x + 1, 2 * y),
                (2 * x, 2 * y + 1),
                (2 * x + 1, 2 * y + 1),
            ];
            for c in 0..3 {
                let sum: f32 = quad
                    .iter()
                    .map(|&(xx, yy)| srgb_to_linear(at(xx, yy, c)))
                    .sum();
                out[(y * h + x) * 4 + c] = linear_to_srgb(sum * 0.25);
            }
            let alpha: u32 = quad.iter().map(|&(xx, yy)| at(xx, yy, 3) as u32).sum();
            out[(y * h + x) * 4 + 3] = ((alpha + 2) / 4) as u8;
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
    for (layer, texture) in textures.iter().enumerate() {
        check(scene_name, layer, texture)?;
    }
    let size = layer_size(
        textures,
        ctx.device
            .limits()
            .max_texture_dimension_2d
            .min(MAX_LAYER_SIZE),
    );
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
        assert_eq!(layer_size(&[Texture::white()], MAX_LAYER_SIZE), 1);
        assert_eq!(
            layer_size(&[Texture::white(), t(300, 200)], MAX_LAYER_SIZE),
            512
        );
        assert_eq!(layer_size(&[t(8192, 10)], MAX_LAYER_SIZE), MAX_LAYER_SIZE);
        assert_eq!(
            layer_size(&[t(8192, 10)], 1000),
            512,
            "a device limit below the cap"
        );
    }

    /// Black and white average to 50 % linear light, sRGB 188; an average of the stored bytes
    /// would give 128 and darken every distant high-contrast texture.
    #[test]
    fn half_averages_2x2_blocks_in_linear_light() {
        let rgba: Vec<u8> = [0u8, 255, 255, 0]
            .iter()
            .flat_map(|&v| [v, v / 2, 0, v])
            .collect();
        let mean_g = linear_to_srgb(srgb_to_linear(127) * 0.5);
        assert_eq!(half(&rgba, 2), vec![188, mean_g, 0, 128]);
        let grey: Vec<u8> = [[90u8, 90, 90, 255]; 4].concat();
        assert_eq!(half(&grey, 2), vec![90, 90, 90, 255], "flat stays flat");
    }

    #[test]
    fn resizing_keeps_flat_colour_and_the_linear_mean() {
        let flat = Texture {
            width: 3,
            height: 5,
            rgba: [[200u8, 100, 30, 255]; 15].concat(),
        };
        let up = resized(&flat, 8);
        assert_eq!(up.len(), 8 * 8 * 4);
        assert!(
            up.chunks_exact(4).all(|p| p == [200, 100, 30, 255]),
            "{up:?}"
        );
        // A 2×2 checker shrunk to one texel is its linear-light mean.
        let checker = Texture {
            width: 2,
            height: 2,
            rgba: [[255u8; 4], [0, 0, 0, 255], [0, 0, 0, 255], [255; 4]].concat(),
        };
        let down = resized(&checker, 1);
        assert!(down[0].abs_diff(188) <= 1, "{down:?}");
    }

    #[test]
    fn malformed_textures_are_errors_naming_the_scene_and_layer() {
        let short = Texture {
            width: 4,
            height: 4,
            rgba: vec![0; 60],
        };
        let err = check("room.glb", 3, &short).unwrap_err().to_string();
        assert!(
            err.starts_with("room.glb: texture layer 3:") && err.contains("64"),
            "{err}"
        );
        let empty = Texture {
            width: 0,
            height: 7,
            rgba: vec![],
        };
        let err = check("s", 1, &empty).unwrap_err().to_string();
        assert!(err.contains("empty"), "{err}");
        assert!(check("s", 0, &Texture::white()).is_ok());
    }
}
