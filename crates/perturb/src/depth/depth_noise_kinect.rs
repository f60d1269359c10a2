//! depth_noise_kinect: the axial noise of a structured-light sensor, σ(z) = 0.0012 +
//! 0.0019·(z − 0.4)² metres, measured for the Kinect v1 by Nguyen, Izadi & Lovell (2012),
//! "Modeling Kinect Sensor Noise for Improved 3D Reconstruction and Tracking", eq. 2 (axial noise
//! at 10–60° incidence). Severity k multiplies σ(z): 1 is a real Kinect v1, 5 a five times
//! noisier sensor. Lateral noise and the angle dependence are not modelled.

use rslam_core::DepthImage;

use super::depth_noise::add_noise;
use super::depth_pass::DepthPointwise;
use crate::image::color_pass::KeyedParams;
use crate::perturbation::{Between, CatalogueEntry, FrameKey, Group};
use crate::twin::{Tolerance, Twin};

const NAME: &str = "depth_noise_kinect";
const SHADER: &str = "perturb/depth/depth_noise_kinect.wgsl";
const PURPOSE_NOISE: u32 = 0;

/// Multiplier of the sensor's σ(z) per severity (our choice; 1 = Kinect v1).
pub const MULTIPLIER: [f32; 5] = [1.0, 2.0, 3.0, 4.0, 5.0];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Depth,
    description: "Kinect v1 axial noise, σ(z) = k(0.0012 + 0.0019(z-0.4)²) m (Nguyen et al. 2012)",
    parameters: |s| format!("k={}", MULTIPLIER[s as usize - 1]),
    build: |kit| {
        DepthPointwise::boxed(kit, SHADER, |_, key| KeyedParams {
            key: key.rng(NAME, PURPOSE_NOISE).0,
            values: [key.interpolate(0.0, &MULTIPLIER) as f32, 0.0, 0.0, 0.0],
        })
    },
    between: Between::Interpolated("k linear from 0"),
    explicit: None,
    twin: Twin::Depth(twin),
    // GPU log/cos vs Rust's in the Box-Muller draw, scaled by σ(z) of a few millimetres.
    twin_tolerance: Tolerance {
        metres: 1e-5,
        ..Tolerance::EXACT
    },
    uniforms: &[KeyedParams::layout(SHADER)],
};

/// σ(z) of the Kinect v1 in metres (Nguyen et al. 2012, eq. 2).
pub fn kinect_sigma(z: f32) -> f32 {
    0.0012 + 0.0019 * (z - 0.4) * (z - 0.4)
}

/// CPU twin of `depth_noise_kinect.wgsl`.
pub fn twin(depth: &DepthImage, key: &FrameKey) -> DepthImage {
    let k = key.interpolate(0.0, &MULTIPLIER) as f32;
    add_noise(depth, &key.rng(NAME, PURPOSE_NOISE), |z| {
        k * kinect_sigma(z)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    /// On fronto-parallel planes at 1 m and 3 m the noise std is k·σ(z): 2.1 mm and 14.0 mm.
    #[test]
    fn noise_grows_with_squared_depth() {
        let (w, h) = (200u32, 200u32);
        for z in [1.0f32, 3.0] {
            let depth = DepthImage {
                width: w,
                height: h,
                data: vec![z; (w * h) as usize],
            };
            let out = testing::run_depth(&ENTRY, &testing::key(4, 2), &depth);
            let n = out.data.len() as f64;
            let mean = out.data.iter().map(|&v| v as f64).sum::<f64>() / n;
            let std = (out
                .data
                .iter()
                .map(|&v| (v as f64 - mean).powi(2))
                .sum::<f64>()
                / n)
                .sqrt();
            let sigma = 2.0 * kinect_sigma(z) as f64;
            assert!(
                (mean - z as f64).abs() < 5.0 * sigma / n.sqrt(),
                "z={z}: mean {mean}"
            );
            assert!(
                (std / sigma - 1.0).abs() < 0.02,
                "z={z}: std {std} vs {sigma}"
            );
        }
    }

    #[test]
    fn seeded() {
        testing::assert_seeded(&ENTRY, 3);
    }
}
