//! vignetting: illumination falling off towards the corners by the cos⁴ law of natural
//! vignetting, gain cos⁴θ = 1 / (1 + tan²θ_c·ρ²)² at normalised radius ρ (1 at the corners),
//! θ_c the half-diagonal field angle; applied in linear light.

use super::color_pass::{KeyedParams, PointwisePass};
use crate::image_f32::{linear_to_srgb, srgb_to_linear, RgbF32};
use crate::perturbation::{Between, CatalogueEntry, FrameKey, Group};
use crate::twin::{Tolerance, Twin};

const NAME: &str = "vignetting";
const SHADER: &str = "perturb/image/vignetting.wgsl";

/// Gain left in the corners per severity (rslam's own scale: a mild wide-angle lens to a
/// strongly vignetting one).
pub const CORNER_GAIN: [f32; 5] = [0.8, 0.65, 0.5, 0.35, 0.2];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "darkens towards the corners by the cos⁴ law (linear light); the corners keep the gain given",
    parameters: |s| format!("corner gain {}", CORNER_GAIN[s as usize - 1]),
    build: |kit| {
        PointwisePass::boxed(kit, SHADER, |key| KeyedParams {
            key: [0; 4],
            values: [falloff(key), 0.0, 0.0, 0.0],
        })
    },
    between: Between::Interpolated("corner gain linear from 1"),
    explicit: None,
    twin: Twin::Color(twin),
    // pow in the sRGB transfer function differs in the last bits on the GPU.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[KeyedParams::layout(SHADER)],
};

/// tan²θ_c, so that the corner gain 1 / (1 + tan²θ_c)² is the severity's.
fn falloff(key: &FrameKey) -> f32 {
    1.0 / (key.interpolate(1.0, &CORNER_GAIN) as f32).sqrt() - 1.0
}

/// CPU twin of `vignetting.wgsl`.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let a = falloff(key);
    let centre = [
        (image.width as f32 - 1.0) * 0.5,
        (image.height as f32 - 1.0) * 0.5,
    ];
    let corner = centre[0].hypot(centre[1]);
    image.map_pixels(|x, y, p| {
        let (dx, dy) = (
            (x as f32 - centre[0]) / corner,
            (y as f32 - centre[1]) / corner,
        );
        let q = 1.0 + a * (dx * dx + dy * dy);
        p.map(|c| linear_to_srgb(srgb_to_linear(c) / (q * q)) + 0.5 / 255.0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    /// A white frame keeps white at the centre and the severity's gain (in linear light) in the
    /// corners.
    #[test]
    fn corners_keep_the_corner_gain_and_the_centre_is_untouched() {
        let white = RgbF32 {
            width: 41,
            height: 31,
            data: vec![[1.0; 3]; 41 * 31],
        };
        for severity in 1..=5 {
            let out = twin(&white, &testing::key(0, severity)).to_rgb8();
            let centre = out.data[((15 * 41 + 20) * 3) as usize];
            assert_eq!(centre, 255);
            let corner = srgb_to_linear(out.data[0] as f32 / 255.0);
            let want = CORNER_GAIN[severity as usize - 1];
            assert!(
                (corner - want).abs() < 0.01,
                "severity {severity}: {corner} vs {want}"
            );
        }
    }
}
