//! Float images for the CPU twins: values in [0, 1] as the shaders see them.

use rslam_core::RgbImage;

/// RGB image of f32 in [0, 1], rows top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct RgbF32 {
    pub width: u32,
    pub height: u32,
    pub data: Vec<[f32; 3]>,
}

impl RgbF32 {
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            data: vec![[0.0; 3]; width as usize * height as usize],
        }
    }

    /// From 8-bit values, as `textureLoad` of an `Rgba8Unorm` texture reads them.
    pub fn from_rgb8(image: &RgbImage) -> Self {
        let data = image
            .data
            .chunks_exact(3)
            .map(|p| [p[0], p[1], p[2]].map(|v| v as f32 / 255.0))
            .collect();
        Self {
            width: image.width,
            height: image.height,
            data,
        }
    }

    /// Quantised by truncation like `np.uint8(clip(x, 0, 1) * 255)` (WGSL `truncate8`).
    pub fn to_rgb8(&self) -> RgbImage {
        let data = self.data.iter().flat_map(|p| p.map(truncate8)).collect();
        RgbImage {
            width: self.width,
            height: self.height,
            data,
        }
    }

    pub fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    pub fn at(&self, x: u32, y: u32) -> [f32; 3] {
        self.data[self.index(x, y)]
    }

    /// The pixel at (x, y) with coordinates clamped into the image (edge replicate).
    pub fn at_clamped(&self, x: i64, y: i64) -> [f32; 3] {
        let x = x.clamp(0, self.width as i64 - 1) as u32;
        let y = y.clamp(0, self.height as i64 - 1) as u32;
        self.at(x, y)
    }

    /// Applies `f(x, y, pixel)` to every pixel: the shape of every per-pixel CPU twin.
    pub fn map_pixels(&self, f: impl Fn(u32, u32, [f32; 3]) -> [f32; 3]) -> Self {
        let width = self.width.max(1);
        Self {
            width: self.width,
            height: self.height,
            data: self
                .data
                .iter()
                .enumerate()
                .map(|(i, &p)| f(i as u32 % width, i as u32 / width, p))
                .collect(),
        }
    }

    /// Applies `f` to every pixel.
    pub fn map(&self, f: impl Fn([f32; 3]) -> [f32; 3]) -> Self {
        Self {
            width: self.width,
            height: self.height,
            data: self.data.iter().map(|&p| f(p)).collect(),
        }
    }
}

/// One channel quantised by truncation (WGSL `truncate8`, which stores floor(v·255)/255).
pub fn truncate8(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).floor() as u8
}

/// sRGB-encoded value in [0, 1] → linear light (WGSL `srgb_to_linear`, IEC 61966-2-1).
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear light → sRGB-encoded value in [0, 1], clipped (WGSL `linear_to_srgb`).
pub fn linear_to_srgb(c: f32) -> f32 {
    let x = c.clamp(0.0, 1.0);
    if x <= 0.0031308 {
        x * 12.92
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}
