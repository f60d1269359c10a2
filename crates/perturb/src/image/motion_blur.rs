//! motion_blur: imagecorruptions' `motion_blur`, a one-sided line kernel of 2·radius+1 taps with
//! Gaussian weights along an angle drawn uniformly in ±45° per frame, edges replicated.

use rslam_gpu::FrameTextures;

use super::color_pass::ColorPass;
use super::kernels::{apply_line_taps, motion_line_taps, store_truncated};
use super::kernels::{LineKernelUniform, LineTap};
use crate::image_f32::RgbF32;
use crate::perturbation::{Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::rng::RngKey;
use crate::severity::Severity;
use crate::twin::{Tolerance, Twin};
use crate::PerturbError;

const NAME: &str = "motion_blur";
const SHADER: &str = "perturb/image/motion_blur.wgsl";

/// (radius, σ) per severity (docs/src/perturbations.md §3, imagecorruptions `motion_blur`).
pub const RADIUS_SIGMA: [(u32, f64); 5] = [(10, 3.0), (15, 5.0), (15, 8.0), (15, 12.0), (20, 15.0)];

/// The blur direction is uniform in [−45°, 45°) per frame (`np.random.uniform(-45, 45)`).
const ANGLE_RANGE: (f64, f64) = (-45.0, 45.0);

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "motion blur: one-sided Gaussian line kernel at a random angle in ±45° per frame",
    parameters: |s| {
        let (radius, sigma) = RADIUS_SIGMA[s as usize - 1];
        format!("radius={radius}px σ={sigma}px")
    },
    build: |kit| Ok(Box::new(MotionBlur::new(kit)?)),
    between: Between::Interpolated("radius (rounded) and σ linear from 0"),
    explicit: None,
    twin: Twin::Color(twin),
    // f32 weighted sums in another order.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[LineKernelUniform::layout(SHADER)],
};

/// A per-frame angle in degrees, uniform in `range`, from the frame's stream `purpose`.
pub(crate) fn frame_angle(key: RngKey, range: (f64, f64)) -> f64 {
    range.0 + (range.1 - range.0) * key.uniform_f64([0; 4])
}

/// The frame's line taps at `severity` for a `width`×`height` frame: radius and σ linear
/// between the table's rows from (0, 0) at severity 0, the radius rounded to whole pixels.
fn frame_taps(seed: u64, frame: u32, severity: Severity, width: u32, height: u32) -> Vec<LineTap> {
    let radius = severity
        .interpolate(0.0, &RADIUS_SIGMA.map(|(r, _)| r as f64))
        .round() as u32;
    let sigma = severity.interpolate(0.0, &RADIUS_SIGMA.map(|(_, s)| s));
    let angle = frame_angle(RngKey::new(seed, NAME, frame, 0), ANGLE_RANGE);
    motion_line_taps(radius, sigma, angle, width, height)
}

struct MotionBlur {
    pass: ColorPass,
}

impl MotionBlur {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        Ok(Self {
            pass: ColorPass::runs::<LineKernelUniform>(kit, SHADER)?,
        })
    }
}

impl GpuPerturbation for MotionBlur {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        let taps = frame_taps(key.seed, key.frame, key.severity, kit.width, kit.height);
        let params = LineKernelUniform::new(&taps).ok_or_else(|| PerturbError::Unsupported {
            name: NAME.into(),
            message: format!("{} taps do not fit the shader's kernel", taps.len()),
        })?;
        self.pass.encode(kit, encoder, frame, &params, &[]);
        Ok(())
    }
}

/// CPU twin of `motion_blur.wgsl`.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let taps = frame_taps(key.seed, key.frame, key.severity, image.width, image.height);
    let blurred = apply_line_taps(&image.data, image.width, image.height, &taps);
    RgbF32 {
        width: image.width,
        height: image.height,
        data: blurred
            .into_iter()
            .map(|p| p.map(store_truncated))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn a_dot_smears_into_a_line_at_the_frame_angle() {
        // One white pixel on black: its light lands on the pixels whose taps read it, i.e. at
        // −(dx, dy) of each tap, with the tap's weight.
        let mut image = RgbF32::new(64, 64);
        let centre = image.index(32, 32);
        image.data[centre] = [1.0; 3];
        let key = FrameKey {
            frame: 4,
            ..testing::key(9, 1)
        };
        let out = twin(&image, &key);
        let taps = frame_taps(9, 4, Severity::whole(1).unwrap(), 64, 64);
        for t in &taps {
            let at = out.at((32 - t.dx) as u32, (32 - t.dy) as u32)[0];
            assert!(at >= t.weight - 1.0 / 255.0, "tap {t:?}: {at}");
        }
        let lit = out.data.iter().filter(|p| p[0] > 0.0).count();
        assert!(lit <= taps.len(), "{lit} pixels lit by {} taps", taps.len());
        let angle = frame_angle(RngKey::new(9, NAME, 4, 0), ANGLE_RANGE);
        assert!((-45.0..45.0).contains(&angle));
    }

    #[test]
    fn angle_varies_by_frame_and_seed_and_repeats() {
        let angle = |seed, frame| frame_angle(RngKey::new(seed, NAME, frame, 0), ANGLE_RANGE);
        assert_eq!(angle(1, 2), angle(1, 2));
        assert_ne!(angle(1, 2), angle(1, 3));
        assert_ne!(angle(1, 2), angle(2, 2));
    }
}
