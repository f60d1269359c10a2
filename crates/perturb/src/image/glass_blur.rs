//! glass_blur: imagecorruptions' `glass_blur`: Gaussian blur (σ) truncated to 8 bits, then
//! `iterations` sweeps that move pixels by random offsets in [−δ, δ−1], then the blur again.
//! Their sweep swaps pixels sequentially from the bottom-right; ours is a parallel gather per
//! sweep (docs/src/perturbations.md §3 allows it), which keeps PSNR within ~1.5 dB of theirs.

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use super::gaussian_blur::{blur_twin, GaussianPasses};
use super::kernels::Kernel1dUniform;
use super::separable::Channels;
use crate::image_f32::RgbF32;
use crate::perturbation::{view, Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::rng::RngKey;
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, UniformLayout};
use crate::PerturbError;

const NAME: &str = "glass_blur";
const SHADER: &str = "perturb/image/glass_blur.wgsl";

/// (σ, max shift δ, iterations) per severity (docs/src/perturbations.md §3, imagecorruptions).
pub const PARAMS: [(f64, i32, u32); 5] = [
    (0.7, 1, 2),
    (0.9, 2, 1),
    (1.0, 2, 3),
    (1.1, 3, 2),
    (1.5, 4, 2),
];

const MAX_ITERATIONS: usize = 3;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "glass blur: blur, local random pixel shifts (sweeps), blur again",
    parameters: |s| {
        let (sigma, delta, iterations) = PARAMS[s as usize - 1];
        format!("σ={sigma}px δ={delta}px iterations={iterations}")
    },
    build: |kit| Ok(Box::new(GlassBlur::new(kit)?)),
    between: Between::WholeOnly(
        "its iterations go 2, 1, 3, 2, 2: no parameter path between the rows",
    ),
    explicit: None,
    twin: Twin::Color(twin),
    // The blurs' f32 weighted sums in another order; the sweeps move whole pixels.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[
        Kernel1dUniform::layout(Channels::Rgb8.shaders()[0]),
        Kernel1dUniform::layout(Channels::Rgb8.shaders()[1]),
        UniformLayout {
            rust: rust_layout!(Sweep {
                key,
                delta,
                iteration
            }),
            wgsl: "Sweep",
            shader: SHADER,
        },
    ],
};

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Sweep {
    key: [u32; 4],
    delta: i32,
    iteration: u32,
    _pad: [u32; 2],
}

struct GlassBlur {
    blur: GaussianPasses,
    sweep: wgpu::ComputePipeline,
    /// One uniform per sweep: all are written before the frame's submission.
    sweeps: Vec<wgpu::Buffer>,
}

impl GlassBlur {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        Ok(Self {
            blur: GaussianPasses::new(kit)?,
            sweep: kit.pipeline(SHADER)?,
            sweeps: (0..MAX_ITERATIONS)
                .map(|_| kit.uniform_buffer::<Sweep>("glass sweep"))
                .collect(),
        })
    }
}

impl GpuPerturbation for GlassBlur {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        let (sigma, delta, iterations) = PARAMS[key.level()];
        self.blur.set_sigma(kit, NAME, sigma)?;
        let frame_view = frame.color_view();
        let scratch = view(&kit.scratch.color);
        // Blur into scratch, sweep back and forth, blur from wherever the sweeps ended.
        self.blur.encode(kit, encoder, frame_view, &scratch);
        let rng = key.rng(NAME, 0);
        for (i, buffer) in self.sweeps.iter().take(iterations as usize).enumerate() {
            let params = Sweep {
                key: rng.0,
                delta,
                iteration: i as u32,
                _pad: [0; 2],
            };
            kit.write_uniform(buffer, &params);
            let (from, to) = if i % 2 == 0 {
                (&scratch, frame_view)
            } else {
                (frame_view, &scratch)
            };
            let bind_group = kit.bind_group(
                &self.sweep,
                "glass sweep",
                &[
                    wgpu::BindingResource::TextureView(from),
                    wgpu::BindingResource::TextureView(to),
                    buffer.as_entire_binding(),
                ],
            );
            kit.dispatch(encoder, &self.sweep, &bind_group, "glass sweep");
        }
        let swept = if iterations % 2 == 1 {
            frame_view
        } else {
            &scratch
        };
        self.blur.encode(kit, encoder, swept, frame_view);
        Ok(())
    }
}

/// One sweep: the source position each pixel takes (the twin of `glass_blur.wgsl`).
fn sweep_source(
    rng: &RngKey,
    delta: i32,
    iteration: u32,
    x: u32,
    y: u32,
    w: u32,
    h: u32,
) -> (u32, u32) {
    let (xi, yi) = (x as i32, y as i32);
    let inside = xi > delta && yi > delta && xi <= w as i32 - delta && yi <= h as i32 - delta;
    if !inside {
        return (x, y);
    }
    let bits = rng.draw([x, y, iteration, 0]);
    let span = (2 * delta) as u32;
    let dx = (bits[0] % span) as i32 - delta;
    let dy = (bits[1] % span) as i32 - delta;
    ((xi + dx) as u32, (yi + dy) as u32)
}

/// CPU twin of glass_blur.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let (sigma, delta, iterations) = PARAMS[key.level()];
    let rng = key.rng(NAME, 0);
    let (w, h) = (image.width, image.height);
    let mut current = blur_twin(image, sigma);
    for i in 0..iterations {
        let mut next = current.clone();
        for y in 0..h {
            for x in 0..w {
                let (sx, sy) = sweep_source(&rng, delta, i, x, y, w, h);
                let index = next.index(x, y);
                next.data[index] = current.at(sx, sy);
            }
        }
        current = next;
    }
    blur_twin(&current, sigma)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn shifts_cover_minus_delta_to_delta_minus_one_uniformly() {
        let rng = RngKey::new(1, NAME, 0, 0);
        let delta = 3;
        let mut counts = [0u32; 6];
        for y in 10..60 {
            for x in 10..60 {
                let (sx, _) = sweep_source(&rng, delta, 0, x, y, 100, 100);
                counts[(sx as i32 - x as i32 + delta) as usize] += 1;
            }
        }
        // 2500 draws over 6 offsets: each ~417, allow ±5 binomial standard deviations.
        for c in counts {
            assert!(
                (c as f64 - 2500.0 / 6.0).abs() < 5.0 * (2500.0f64 / 6.0).sqrt(),
                "{counts:?}"
            );
        }
        // The border band of width δ (and the row/column δ itself) is left in place.
        assert_eq!(sweep_source(&rng, delta, 0, 3, 50, 100, 100), (3, 50));
        assert_eq!(sweep_source(&rng, delta, 0, 50, 98, 100, 100), (50, 98));
    }

    #[test]
    fn seeded() {
        let clean = testing::test_image(64, 48);
        let a = testing::run_color(&ENTRY, 3, 1, &clean);
        let b = testing::run_color(&ENTRY, 3, 1, &clean);
        let c = testing::run_color(&ENTRY, 3, 2, &clean);
        assert_eq!(a.data, b.data);
        assert_ne!(a.data, c.data);
    }
}
