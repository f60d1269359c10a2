//! speckle_noise: x + x·N(0, σ) per pixel and channel (imagecorruptions `speckle_noise`).

use super::color_pass::{KeyedParams, PointwisePass};
use crate::image_f32::RgbF32;
use crate::perturbation::{Between, CatalogueEntry, FrameKey, Group};
use crate::twin::{Tolerance, Twin};

const NAME: &str = "speckle_noise";
const SHADER: &str = "perturb/image/speckle_noise.wgsl";
const PURPOSE_NOISE: u32 = 0;

/// σ per severity (docs/src/perturbations.md §3, imagecorruptions `speckle_noise`).
pub const SIGMA: [f32; 5] = [0.15, 0.20, 0.35, 0.45, 0.60];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "multiplicative Gaussian noise x·(1 + N(0,σ)), per pixel and channel",
    parameters: |s| format!("σ={}", SIGMA[s as usize - 1]),
    build: |kit| {
        PointwisePass::boxed(kit, SHADER, |key| KeyedParams {
            key: key.rng(NAME, PURPOSE_NOISE).0,
            values: [key.interpolate(0.0, &SIGMA) as f32, 0.0, 0.0, 0.0],
        })
    },
    between: Between::Interpolated("σ linear from 0"),
    explicit: None,
    twin: Twin::Color(twin),
    // GPU and Rust Box-Muller (log, cos) differ in the last bits.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[KeyedParams::layout(SHADER)],
};

/// CPU twin of `speckle_noise.wgsl`.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let rng = key.rng(NAME, PURPOSE_NOISE);
    let sigma = key.interpolate(0.0, &SIGMA) as f32;
    image.map_pixels(|x, y, p| {
        let n = rng.normal3([x, y, 0, 0]);
        std::array::from_fn(|c| p[c] + p[c] * sigma * n[c])
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn noise_scales_with_the_value() {
        // On grey x the law is x + N(0, x·σ); black stays black.
        let x = 100.0 / 255.0;
        let grey = testing::uniform_image(256, 256, 100);
        for severity in 1..=5 {
            let out = testing::run_color(&ENTRY, severity, 1, &grey);
            let sigma = x * SIGMA[severity as usize - 1] as f64;
            let (mean, std) = testing::level_stats(&testing::clipped_normal_levels(x, sigma));
            testing::assert_stats(
                testing::stats(&out),
                mean,
                std,
                &format!("severity {severity}"),
            );
        }
        let black = testing::uniform_image(32, 32, 0);
        assert_eq!(testing::run_color(&ENTRY, 5, 1, &black), black);
    }

    #[test]
    fn seeded() {
        testing::assert_seeded(&ENTRY, 3);
    }
}
