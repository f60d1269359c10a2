//! brightness: V += ΔV in HSV, as imagecorruptions' `brightness` (skimage rgb2hsv → clip → hsv2rgb).

use super::color_pass::{KeyedParams, PointwisePass};
use super::hsv::{hsv_to_rgb, rgb_to_hsv};
use crate::image_f32::RgbF32;
use crate::perturbation::{Between, CatalogueEntry, FrameKey, Group};
use crate::twin::{Tolerance, Twin};

const NAME: &str = "brightness";
const SHADER: &str = "perturb/image/brightness.wgsl";

/// ΔV per severity (docs/src/perturbations.md §3, imagecorruptions `brightness`).
pub const DELTA_V: [f32; 5] = [0.1, 0.2, 0.3, 0.4, 0.5];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "brightens: adds ΔV to the HSV value channel (clipped to 1)",
    parameters: |s| format!("ΔV={}", DELTA_V[s as usize - 1]),
    build: |kit| {
        PointwisePass::boxed(kit, SHADER, |key| KeyedParams {
            key: [0; 4],
            values: [key.interpolate(0.0, &DELTA_V) as f32, 0.0, 0.0, 0.0],
        })
    },
    between: Between::Interpolated("ΔV linear from 0"),
    explicit: None,
    twin: Twin::Color(twin),
    // The HSV round trip in f32: divisions that differ in the last bit.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[KeyedParams::layout(SHADER)],
};

/// CPU twin of `brightness.wgsl`.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let delta = key.interpolate(0.0, &DELTA_V) as f32;
    image.map(|p| {
        let [h, s, v] = rgb_to_hsv(p);
        hsv_to_rgb([h, s, (v + delta).clamp(0.0, 1.0)])
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn brightness_raises_value_by_delta() {
        // Pure grey 0.2 → V = 0.2 + 0.3 at severity 3, hue and saturation stay 0.
        let grey = RgbF32 {
            width: 1,
            height: 1,
            data: vec![[0.2; 3]],
        };
        let out = twin(&grey, &testing::key(0, 3)).data[0];
        for c in out {
            assert!((c - 0.5).abs() < 1e-6, "{out:?}");
        }
    }
}
