//! impulse_noise: salt and pepper per pixel and channel (imagecorruptions `impulse_noise`, i.e.
//! skimage `random_noise(mode='s&p', amount)`, salt and pepper equally likely).

use super::color_pass::{KeyedParams, PointwisePass};
use crate::image_f32::RgbF32;
use crate::perturbation::{Between, CatalogueEntry, FrameKey, Group};
use crate::rng;
use crate::twin::{Tolerance, Twin};

const NAME: &str = "impulse_noise";
const SHADER: &str = "perturb/image/impulse_noise.wgsl";
const PURPOSE_NOISE: u32 = 0;

/// Fraction of values replaced, per severity (docs/src/perturbations.md §3, imagecorruptions).
pub const AMOUNT: [f32; 5] = [0.03, 0.06, 0.09, 0.17, 0.27];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description:
        "salt and pepper: each channel value becomes 0 or 1 (equal odds) with probability `amount`",
    parameters: |s| format!("amount={}", AMOUNT[s as usize - 1]),
    build: |kit| {
        PointwisePass::boxed(kit, SHADER, |key| KeyedParams {
            key: key.rng(NAME, PURPOSE_NOISE).0,
            values: [key.interpolate(0.0, &AMOUNT) as f32, 0.0, 0.0, 0.0],
        })
    },
    between: Between::Interpolated("amount linear from 0"),
    explicit: None,
    twin: Twin::Color(twin),
    // Each value is kept or replaced by 0 or 1, chosen from the same integer hash.
    twin_tolerance: Tolerance::EXACT,
    uniforms: &[KeyedParams::layout(SHADER)],
};

/// CPU twin of `impulse_noise.wgsl`.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let rng = key.rng(NAME, PURPOSE_NOISE);
    let amount = key.interpolate(0.0, &AMOUNT) as f32;
    image.map_pixels(|x, y, p| {
        let words = rng.draw([x, y, 0, 0]);
        std::array::from_fn(|c| {
            let u = rng::uniform(words[c]);
            if u < 0.5 * amount {
                1.0
            } else if u < amount {
                0.0
            } else {
                p[c]
            }
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn replaced_fraction_is_the_amount_half_salt_half_pepper() {
        let grey = testing::uniform_image(256, 256, 128);
        for severity in 1..=5 {
            let out = testing::run_color(&ENTRY, severity, 2, &grey);
            let n = out.data.len() as f64;
            let salt = out.data.iter().filter(|&&v| v == 255).count() as f64 / n;
            let pepper = out.data.iter().filter(|&&v| v == 0).count() as f64 / n;
            let untouched = out.data.iter().filter(|&&v| v == 128).count() as f64 / n;
            assert!((salt + pepper + untouched - 1.0).abs() < 1e-12);
            let p = AMOUNT[severity as usize - 1] as f64 / 2.0;
            let tol = 5.0 * (p * (1.0 - p) / n).sqrt();
            assert!(
                (salt - p).abs() < tol,
                "severity {severity}: salt {salt} vs {p}"
            );
            assert!(
                (pepper - p).abs() < tol,
                "severity {severity}: pepper {pepper} vs {p}"
            );
        }
    }

    #[test]
    fn seeded() {
        testing::assert_seeded(&ENTRY, 3);
    }
}
