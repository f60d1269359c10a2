//! zoom_blur: the mean of the image and its centre zooms, as imagecorruptions' `zoom_blur`
//! (`clipped_zoom` = centre crop + SciPy `zoom(order=1)`).

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use super::color_pass::ColorPass;
use super::kernels::store_truncated;
use crate::image_f32::RgbF32;
use crate::perturbation::{Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::severity::Severity;
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, UniformLayout};
use crate::PerturbError;

const NAME: &str = "zoom_blur";
const SHADER: &str = "perturb/image/zoom_blur.wgsl";

/// Zoom factors `np.arange(1, stop, step)` per severity (docs/src/perturbations.md §3, imagecorruptions
/// `zoom_blur`).
pub const ZOOM_RANGE: [(f64, f64); 5] = [
    (1.11, 0.01),
    (1.16, 0.01),
    (1.21, 0.02),
    (1.26, 0.02),
    (1.31, 0.03),
];

/// Zoom slots in the shader's uniform.
const MAX_ZOOMS: usize = 16;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "zoom blur: mean of the frame and its centre zooms (factors from 1 in steps)",
    parameters: |s| {
        let (stop, step) = ZOOM_RANGE[s as usize - 1];
        format!(
            "zooms 1..{stop} step {step} ({} layers)",
            zoom_factors(Severity::whole(s).expect("a severity 1..=5")).len()
        )
    },
    build: |kit| Ok(Box::new(ZoomBlur::new(kit)?)),
    between: Between::Interpolated("stop linear from 1, step linear from the first row's"),
    explicit: None,
    twin: Twin::Color(twin),
    // f32 bilinear weights and sums in another order.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[UniformLayout {
        rust: rust_layout!(Zooms {
            count,
            inverse_total,
            windows
        }),
        wgsl: "Zooms",
        shader: SHADER,
    }],
};

/// The factors as `np.arange(1, stop, step)` yields them: ceil((stop − 1)/step) values
/// 1 + i·step (float rounding included, e.g. 12 values for severity 1). Between the table's
/// rows stop and step are linear, from stop 1 (no zoomed layer) and the first row's step at 0.
pub fn zoom_factors(severity: Severity) -> Vec<f64> {
    let stop = severity.interpolate(1.0, &ZOOM_RANGE.map(|(stop, _)| stop));
    let step = severity.interpolate(ZOOM_RANGE[0].1, &ZOOM_RANGE.map(|(_, step)| step));
    let count = ((stop - 1.0) / step).ceil() as usize;
    (0..count).map(|i| 1.0 + i as f64 * step).collect()
}

/// Where output pixel p of one zoom layer reads along an axis of `size` pixels: top + p·scale,
/// for p < `zoomed` (also used by snow).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AxisWindow {
    pub top: f32,
    pub scale: f32,
    pub zoomed: u32,
    /// Source pixels the window reads: top .. top + crop.
    pub crop: u32,
}

/// `clipped_zoom` along one axis: crop ceil(size/z) centred, zoomed to round(crop·z) samples
/// with corner-aligned coordinates.
pub(crate) fn axis_window(size: u32, zoom: f64) -> AxisWindow {
    let crop = (size as f64 / zoom).ceil() as i64;
    let top = (size as i64 - crop).div_euclid(2);
    let zoomed = (crop as f64 * zoom).round_ties_even() as i64;
    AxisWindow {
        top: top as f32,
        scale: ((crop - 1) as f64 / (zoomed - 1).max(1) as f64) as f32,
        zoomed: zoomed as u32,
        crop: crop as u32,
    }
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Zooms {
    count: i32,
    _pad: [i32; 2],
    inverse_total: f32,
    windows: [[f32; 4]; MAX_ZOOMS],
}

fn zooms(severity: Severity, width: u32, height: u32) -> Zooms {
    let factors = zoom_factors(severity);
    let mut out = Zooms {
        count: factors.len() as i32,
        _pad: [0; 2],
        inverse_total: 1.0 / (factors.len() + 1) as f32,
        windows: [[0.0; 4]; MAX_ZOOMS],
    };
    for (k, &z) in factors.iter().enumerate() {
        let (x, y) = (axis_window(width, z), axis_window(height, z));
        out.windows[k] = [x.top, y.top, x.scale, y.scale];
    }
    out
}

struct ZoomBlur {
    pass: ColorPass,
}

impl ZoomBlur {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        Ok(Self {
            pass: ColorPass::runs::<Zooms>(kit, SHADER)?,
        })
    }
}

impl GpuPerturbation for ZoomBlur {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        let params = zooms(key.severity, kit.width, kit.height);
        self.pass.encode(kit, encoder, frame, &params, &[]);
        Ok(())
    }
}

/// Bilinear read of `image` at (x, y) as the shader does it (right/bottom neighbour clamped).
fn bilinear(image: &RgbF32, x: f32, y: f32) -> [f32; 3] {
    let (bx, by) = (x.floor(), y.floor());
    let (fx, fy) = (x - bx, y - by);
    let (x0, y0) = (bx as i64, by as i64);
    let a = image.at_clamped(x0, y0);
    let b = image.at_clamped(x0 + 1, y0);
    let c = image.at_clamped(x0, y0 + 1);
    let d = image.at_clamped(x0 + 1, y0 + 1);
    std::array::from_fn(|i| {
        let upper = a[i] * (1.0 - fx) + b[i] * fx;
        let lower = c[i] * (1.0 - fx) + d[i] * fx;
        upper * (1.0 - fy) + lower * fy
    })
}

/// CPU twin of `zoom_blur.wgsl`.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let params = zooms(key.severity, image.width, image.height);
    let layers = zoom_factors(key.severity).len();
    let mut out = image.clone();
    for y in 0..image.height {
        for x in 0..image.width {
            let mut sum = image.at(x, y);
            for w in &params.windows[..layers] {
                let v = bilinear(image, w[0] + x as f32 * w[2], w[1] + y as f32 * w[3]);
                sum = std::array::from_fn(|i| sum[i] + v[i]);
            }
            let i = out.index(x, y);
            out.data[i] = sum.map(|s| store_truncated(s * params.inverse_total));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn factors_follow_numpy_arange() {
        let lens: Vec<usize> = (1..=5)
            .map(|s| zoom_factors(Severity::whole(s).unwrap()).len())
            .collect();
        assert_eq!(lens, [12, 16, 11, 13, 11]);
        assert!((zoom_factors(Severity::MAX)[10] - 1.3).abs() < 1e-9);
    }

    #[test]
    fn windows_match_clipped_zoom() {
        // H = 680, z = 1.1: crop ceil(618.18) = 619, top (680 − 619) // 2 = 30,
        // zoomed round(680.9) = 681 rows, scale 618 / 680.
        let w = axis_window(680, 1.1);
        assert_eq!(w.top, 30.0);
        assert!((w.scale - 618.0 / 680.0).abs() < 1e-7);
        assert_eq!(w.zoomed, 681);
        assert_eq!(w.crop, 619);
        let identity = AxisWindow {
            top: 0.0,
            scale: 1.0,
            zoomed: 680,
            crop: 680,
        };
        assert_eq!(axis_window(680, 1.0), identity);
    }

    #[test]
    fn centre_stays_sharp_and_borders_blur() {
        // Zooms about the centre move pixels radially by an amount growing with the distance.
        let clean = testing::test_image(96, 64);
        let image = RgbF32::from_rgb8(&clean);
        let out = twin(&image, &testing::key(0, 5));
        let diff = |x: u32, y: u32| {
            let (a, b) = (image.at(x, y), out.at(x, y));
            (0..3).map(|c| (a[c] - b[c]).abs()).sum::<f32>()
        };
        let centre: f32 = (44..52)
            .flat_map(|x| (28..36).map(move |y| (x, y)))
            .map(|(x, y)| diff(x, y))
            .sum();
        let corner: f32 = (0..8)
            .flat_map(|x| (0..8).map(move |y| (x, y)))
            .map(|(x, y)| diff(x, y))
            .sum();
        assert!(centre < corner, "centre {centre} corner {corner}");
    }
}
