//! depth_noise: z + N(0, c·std(valid z)) per pixel, clamped at 0 (docs/src/perturbations.md §4). The
//! std of the frame's valid depth comes from a GPU reduction in the same command buffer.

use rslam_core::DepthImage;
use rslam_gpu::FrameTextures;

use super::depth_pass::DepthPass;
use crate::image::color_pass::KeyedParams;
use crate::perturbation::{Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::reduce::Reduction;
use crate::twin::{Tolerance, Twin};
use crate::{rng, PerturbError};

const NAME: &str = "depth_noise";
const SHADER: &str = "perturb/depth/depth_noise.wgsl";
const STATS_SHADER: &str = "perturb/depth/depth_noise_stats.wgsl";
const PURPOSE_NOISE: u32 = 0;

/// c per severity: σ = c × std of the frame's valid depth (docs/src/perturbations.md §4).
pub const FACTOR: [f32; 5] = [0.1, 0.2, 0.3, 0.4, 0.5];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Depth,
    description:
        "Gaussian depth noise, σ = c x std of the frame's valid depth; invalid stays invalid",
    parameters: |s| format!("c={}", FACTOR[s as usize - 1]),
    build: |kit| Ok(Box::new(DepthNoise::new(kit)?)),
    between: Between::Interpolated("c linear from 0"),
    explicit: None,
    twin: Twin::Depth(twin),
    // The GPU's f32 Kahan sums of the depth std vs the twin's f64 ones, and GPU log/cos vs
    // Rust's in the Box-Muller draw.
    twin_tolerance: Tolerance {
        metres: 1e-4,
        ..Tolerance::EXACT
    },
    uniforms: &[KeyedParams::layout(SHADER)],
};

struct DepthNoise {
    stats: Reduction,
    pass: DepthPass,
}

impl DepthNoise {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        Ok(Self {
            stats: Reduction::new(kit, STATS_SHADER)?,
            pass: DepthPass::new::<KeyedParams>(kit, SHADER)?,
        })
    }
}

impl GpuPerturbation for DepthNoise {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        self.stats.encode(kit, encoder, frame.depth_view());
        let params = KeyedParams {
            key: key.rng(NAME, PURPOSE_NOISE).0,
            values: [key.interpolate(0.0, &FACTOR) as f32, 0.0, 0.0, 0.0],
        };
        let sums = self.stats.sums().as_entire_binding();
        self.pass.encode(kit, encoder, frame, &params, &[sums]);
        Ok(())
    }
}

/// Population standard deviation of the valid (> 0) depth values; 0 without any.
pub fn valid_depth_std(depth: &DepthImage) -> f32 {
    let valid: Vec<f64> = depth
        .data
        .iter()
        .filter(|&&z| z > 0.0)
        .map(|&z| z as f64)
        .collect();
    if valid.is_empty() {
        return 0.0;
    }
    let mean = valid.iter().sum::<f64>() / valid.len() as f64;
    let var = valid.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / valid.len() as f64;
    var.sqrt() as f32
}

/// Adds `sigma(z)·N(0, 1)` to every valid pixel, clamped at 0: the twin of the depth noise
/// shaders, which draw one normal per pixel from `rng_draw(key, (x, y, 0, 0))`.
pub fn add_noise(depth: &DepthImage, key: &rng::RngKey, sigma: impl Fn(f32) -> f32) -> DepthImage {
    let mut out = depth.clone();
    for y in 0..depth.height {
        for x in 0..depth.width {
            let i = (y * depth.width + x) as usize;
            let z = depth.data[i];
            if z > 0.0 {
                let u = key.draw([x, y, 0, 0]);
                let n = rng::normal_pair(u[0], u[1])[0];
                out.data[i] = (z + sigma(z) * n).max(0.0);
            }
        }
    }
    out
}

/// CPU twin of `depth_noise_stats.wgsl` + `depth_noise.wgsl`.
pub fn twin(depth: &DepthImage, key: &FrameKey) -> DepthImage {
    let sigma = key.interpolate(0.0, &FACTOR) as f32 * valid_depth_std(depth);
    add_noise(depth, &key.rng(NAME, PURPOSE_NOISE), |_| sigma)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    /// On a slanted plane 5..7 m (no clamping), the added noise has mean 0 and std c·std(z);
    /// invalid pixels stay 0.
    #[test]
    fn noise_std_is_c_times_depth_std_and_invalid_stays_invalid() {
        let (w, h) = (256u32, 200u32);
        let mut depth = DepthImage::new(w, h);
        for y in 0..h {
            for x in 0..w {
                let z = if x % 17 == 0 {
                    0.0
                } else {
                    5.0 + 2.0 * x as f32 / w as f32
                };
                depth.data[(y * w + x) as usize] = z;
            }
        }
        let depth_std = valid_depth_std(&depth) as f64;
        for severity in 1..=5 {
            let out = testing::run_depth(&ENTRY, &testing::key(1, severity), &depth);
            let mut diffs = Vec::new();
            for (a, b) in out.data.iter().zip(&depth.data) {
                if *b == 0.0 {
                    assert_eq!(*a, 0.0, "invalid depth became valid");
                } else {
                    diffs.push((a - b) as f64);
                }
            }
            let n = diffs.len() as f64;
            let mean = diffs.iter().sum::<f64>() / n;
            let std = (diffs.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / n).sqrt();
            let sigma = FACTOR[severity as usize - 1] as f64 * depth_std;
            assert!(
                mean.abs() < 5.0 * sigma / n.sqrt(),
                "severity {severity}: mean {mean}"
            );
            assert!(
                (std / sigma - 1.0).abs() < 5.0 / (2.0 * n).sqrt(),
                "severity {severity}: std {std} vs {sigma}"
            );
        }
    }

    #[test]
    fn seeded() {
        testing::assert_seeded(&ENTRY, 3);
    }
}
