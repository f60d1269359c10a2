//! shot_noise: Poisson(x·c)/c per pixel and channel (imagecorruptions `shot_noise`). The sampler
//! is exact at every rate: inversion below λ = 10, Hörmann's PTRS rejection above (as numpy).

use super::color_pass::{KeyedParams, PointwisePass};
use crate::image_f32::RgbF32;
use crate::perturbation::{Between, CatalogueEntry, FrameKey, Group};
use crate::twin::{Tolerance, Twin};

const NAME: &str = "shot_noise";
const SHADER: &str = "perturb/image/shot_noise.wgsl";
const PURPOSE_NOISE: u32 = 0;

/// Photons at full scale per severity (docs/src/perturbations.md §3, imagecorruptions `shot_noise`).
pub const PHOTONS: [f32; 5] = [60.0, 25.0, 12.0, 5.0, 3.0];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "photon noise: Poisson(x·c)/c per pixel and channel, exact Poisson sampler",
    parameters: |s| format!("c={}", PHOTONS[s as usize - 1]),
    build: |kit| {
        PointwisePass::boxed(kit, SHADER, |key| KeyedParams {
            key: key.rng(NAME, PURPOSE_NOISE).0,
            values: [photons(key), 0.0, 0.0, 0.0],
        })
    },
    between: Between::Interpolated("c linear in 1/c (the noise variance) from no noise"),
    explicit: None,
    twin: Twin::Color(twin),
    // PTRS rejection sampling decides on log/exp of uniforms: a last-bit difference between
    // the GPU's and Rust's flips a rare accept/reject and draws another count there.
    twin_tolerance: Tolerance {
        outliers: 1e-3,
        ..Tolerance::ONE_LEVEL
    },
    uniforms: &[KeyedParams::layout(SHADER)],
};

/// Photons per unit intensity at the frame's severity, linear in 1/c (the noise variance) from
/// no noise at severity 0.
fn photons(key: &FrameKey) -> f32 {
    key.interpolate_in(0.0, &PHOTONS, |c| 1.0 / c, |v| 1.0 / v) as f32
}

/// CPU twin of `shot_noise.wgsl`.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let rng = key.rng(NAME, PURPOSE_NOISE);
    let c = photons(key);
    image.map_pixels(|x, y, p| {
        std::array::from_fn(|ch| rng.poisson([x, y, ch as u32], p[ch] * c) / c)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    /// Output levels against the exact law trunc8(min(k/c, 1)), k ~ Poisson(x·c): mean x and
    /// variance x/c before quantisation.
    #[test]
    fn poisson_mean_and_variance() {
        for level in [30u8, 128, 230] {
            let x = level as f64 / 255.0;
            let grey = testing::uniform_image(256, 256, level);
            for severity in 1..=5 {
                let c = PHOTONS[severity as usize - 1] as f64;
                let out = testing::run_color(&ENTRY, severity, 3, &grey);
                let mut levels = [0.0; 256];
                let lambda = x * c;
                let mut pmf = (-lambda).exp();
                for k in 0..400 {
                    if k > 0 {
                        pmf *= lambda / k as f64;
                    }
                    let v = (k as f64 / c).min(1.0);
                    levels[(v * 255.0).floor() as usize] += pmf;
                }
                let (mean, std) = testing::level_stats(&levels);
                testing::assert_stats(
                    testing::stats(&out),
                    mean,
                    std,
                    &format!("level {level} severity {severity}"),
                );
            }
        }
    }

    #[test]
    fn seeded() {
        testing::assert_seeded(&ENTRY, 3);
    }
}
