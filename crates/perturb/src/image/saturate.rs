//! saturate: S' = clip(S·m + o, 0, 1) in HSV (imagecorruptions `saturate`). As there, grey pixels
//! (S = 0, H = 0) take S' = o, i.e. a red tint at severities 4 and 5.

use super::color_pass::{KeyedParams, PointwisePass};
use super::hsv::{hsv_to_rgb, rgb_to_hsv};
use crate::image_f32::RgbF32;
use crate::perturbation::{Between, CatalogueEntry, FrameKey, Group};
use crate::twin::{Tolerance, Twin};

const NAME: &str = "saturate";
const SHADER: &str = "perturb/image/saturate.wgsl";

/// (S multiplier, S offset) per severity (docs/src/perturbations.md §3, imagecorruptions `saturate`).
pub const SATURATION: [(f32, f32); 5] =
    [(0.3, 0.0), (0.1, 0.0), (2.0, 0.0), (5.0, 0.1), (20.0, 0.2)];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "scales HSV saturation by m and adds o (1-2 desaturate, 3-5 oversaturate)",
    parameters: |s| {
        let (m, o) = SATURATION[s as usize - 1];
        format!("m={m} o={o}")
    },
    build: |kit| {
        PointwisePass::boxed(kit, SHADER, |key| {
            let (m, o) = SATURATION[key.level()];
            KeyedParams {
                key: [0; 4],
                values: [m, o, 0.0, 0.0],
            }
        })
    },
    between: Between::WholeOnly(
        "it turns from desaturating (1-2) to oversaturating (3-5), through the clean frame",
    ),
    explicit: None,
    twin: Twin::Color(twin),
    // The HSV round trip in f32: divisions that differ in the last bit.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[KeyedParams::layout(SHADER)],
};

/// CPU twin of `saturate.wgsl`.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let (m, o) = SATURATION[key.level()];
    image.map(|p| {
        let [h, s, v] = rgb_to_hsv(p);
        hsv_to_rgb([h, (s * m + o).clamp(0.0, 1.0), v])
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn saturation_is_scaled_and_grey_is_tinted_by_the_offset() {
        let pixel = |rgb| RgbF32 {
            width: 1,
            height: 1,
            data: vec![rgb],
        };
        // (0.8, 0.4, 0.4): S = 0.5, V = 0.8; severity 1 → S = 0.15 → (0.8, 0.68, 0.68).
        let out = twin(&pixel([0.8, 0.4, 0.4]), &testing::key(0, 1)).data[0];
        for (got, want) in out.iter().zip([0.8, 0.68, 0.68]) {
            assert!((got - want).abs() < 1e-6, "{out:?}");
        }
        // Grey 0.5 at severity 5: S = 0.2, H = 0 → (0.5, 0.4, 0.4).
        let out = twin(&pixel([0.5; 3]), &testing::key(0, 5)).data[0];
        for (got, want) in out.iter().zip([0.5, 0.4, 0.4]) {
            assert!((got - want).abs() < 1e-6, "{out:?}");
        }
    }
}
