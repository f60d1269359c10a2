/// 8-bit sRGB colour image, RGB interleaved, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RgbImage {
    pub width: u32,
    pub height: u32,
    pub data: Vec<u8>,
}

impl RgbImage {
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            data: vec![0; width as usize * height as usize * 3],
        }
    }

    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = (y as usize * self.width as usize + x as usize) * 3;
        [self.data[i], self.data[i + 1], self.data[i + 2]]
    }

    /// RGBA with opaque alpha, the layout GPU textures use.
    pub fn to_rgba(&self) -> Vec<u8> {
        self.data
            .chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect()
    }

    pub fn from_rgba(width: u32, height: u32, rgba: &[u8]) -> Self {
        let data = rgba
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        Self {
            width,
            height,
            data,
        }
    }
}

/// Metric z-depth in metres along the optical axis; 0 = no measurement.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthImage {
    pub width: u32,
    pub height: u32,
    pub data: Vec<f32>,
}

impl DepthImage {
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            data: vec![0.0; width as usize * height as usize],
        }
    }

    pub fn at(&self, x: u32, y: u32) -> f32 {
        self.data[y as usize * self.width as usize + x as usize]
    }

    /// Quantise to 16-bit with `scale` units per metre (rounded, saturating), as depth PNGs store it.
    pub fn to_u16(&self, scale: f64) -> Vec<u16> {
        self.data
            .iter()
            .map(|&z| {
                if z > 0.0 && z.is_finite() {
                    (z as f64 * scale).round().min(u16::MAX as f64) as u16
                } else {
                    0
                }
            })
            .collect()
    }

    pub fn from_u16(width: u32, height: u32, raw: &[u16], scale: f64) -> Self {
        let data = raw.iter().map(|&v| (v as f64 / scale) as f32).collect();
        Self {
            width,
            height,
            data,
        }
    }
}
