//! contrast: (x − μ)·c + μ with μ the per-channel mean of the frame (imagecorruptions
//! `contrast`). The means come from a GPU reduction in the same command buffer.

use rslam_gpu::FrameTextures;

use super::color_pass::{ColorPass, KeyedParams};
use crate::image_f32::RgbF32;
use crate::perturbation::{Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::reduce::Reduction;
use crate::twin::{Tolerance, Twin};
use crate::PerturbError;

const SHADER: &str = "perturb/image/contrast.wgsl";
const MEAN_SHADER: &str = "perturb/image/contrast_mean.wgsl";

/// Contrast factor per severity (docs/src/perturbations.md §3, imagecorruptions `contrast`).
pub const FACTOR: [f32; 5] = [0.4, 0.3, 0.2, 0.1, 0.05];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: "contrast",
    group: Group::Image,
    description: "lowers contrast: scales each channel about its frame mean by c",
    parameters: |s| format!("c={}", FACTOR[s as usize - 1]),
    build: |kit| Ok(Box::new(Contrast::new(kit)?)),
    between: Between::Interpolated("c linear from 1"),
    explicit: None,
    twin: Twin::Color(twin),
    // The GPU's f32 Kahan sums of the means vs the twin's f64 ones.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[KeyedParams::layout(SHADER)],
};

struct Contrast {
    means: Reduction,
    pass: ColorPass,
}

impl Contrast {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        Ok(Self {
            means: Reduction::new(kit, MEAN_SHADER)?,
            pass: ColorPass::runs::<KeyedParams>(kit, SHADER)?,
        })
    }
}

impl GpuPerturbation for Contrast {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        self.means.encode(kit, encoder, frame.color_view());
        let params = KeyedParams {
            key: [0; 4],
            values: [key.interpolate(1.0, &FACTOR) as f32, 0.0, 0.0, 0.0],
        };
        let sums = self.means.sums().as_entire_binding();
        self.pass.encode(kit, encoder, frame, &params, &[sums]);
        Ok(())
    }
}

/// The per-channel means of an image.
pub fn channel_means(image: &RgbF32) -> [f32; 3] {
    let mut sum = [0.0f64; 3];
    for p in &image.data {
        for c in 0..3 {
            sum[c] += p[c] as f64;
        }
    }
    sum.map(|s| (s / image.data.len() as f64) as f32)
}

/// CPU twin of `contrast_mean.wgsl` + `contrast.wgsl`.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let factor = key.interpolate(1.0, &FACTOR) as f32;
    let mean = channel_means(image);
    image.map(|p| std::array::from_fn(|c| (p[c] - mean[c]) * factor + mean[c]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn mean_is_kept_and_deviation_scaled() {
        let image = RgbF32 {
            width: 2,
            height: 1,
            data: vec![[0.2, 0.5, 1.0], [0.6, 0.5, 0.0]],
        };
        let out = twin(&image, &testing::key(0, 1));
        // Means (0.4, 0.5, 0.5); deviations ±0.2, 0, ±0.5 scaled by 0.4.
        let want = [[0.32, 0.5, 0.7], [0.48, 0.5, 0.3]];
        for (p, w) in out.data.iter().zip(want) {
            for c in 0..3 {
                assert!((p[c] - w[c]).abs() < 1e-6, "{:?}", out.data);
            }
        }
    }
}
