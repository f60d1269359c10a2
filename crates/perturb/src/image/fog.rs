//! fog: imagecorruptions' `fog`: x + amplitude · plasma, rescaled by max/(max + amplitude).
//! The plasma is their diamond-square fractal on a wrapping N×N map (N the power of two ≥ the
//! larger side), normalised over the whole map to [0, 1] and cropped; built level by level on
//! the GPU, fresh for every frame.

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use super::color_pass::ColorPass;
use super::kernels::store_truncated;
use super::textures::storage_texture;
use crate::image_f32::RgbF32;
use crate::perturbation::{view, Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::rng::{uniform, RngKey};
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, UniformLayout};
use crate::PerturbError;

const NAME: &str = "fog";
const PLASMA_SHADER: &str = "perturb/image/fog_plasma.wgsl";
const SHADER: &str = "perturb/image/fog.wgsl";

/// (amplitude, plasma wibble decay) per severity (docs/src/perturbations.md §3, imagecorruptions).
pub const AMPLITUDE_DECAY: [(f32, f64); 5] =
    [(1.5, 2.0), (2.0, 2.0), (2.5, 1.7), (2.5, 1.5), (3.0, 1.4)];

/// The first level's wibble (`plasma_fractal`).
const WIBBLE: f64 = 100.0;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "fog: adds a diamond-square plasma fractal, rescaled to keep the image maximum",
    parameters: |s| {
        let (amplitude, decay) = AMPLITUDE_DECAY[s as usize - 1];
        format!("amplitude={amplitude} wibble decay={decay}")
    },
    build: |kit| Ok(Box::new(Fog::new(kit)?)),
    between: Between::Interpolated("amplitude linear from 0, decay linear from the first row's"),
    explicit: None,
    twin: Twin::Color(twin),
    // f32 plasma means and the rescaling, with fused multiply-adds on the GPU.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[
        UniformLayout {
            rust: rust_layout!(Level {
                key,
                step,
                size,
                wibble
            }),
            wgsl: "Level",
            shader: PLASMA_SHADER,
        },
        UniformLayout {
            rust: rust_layout!(FogParams { amplitude }),
            wgsl: "Fog",
            shader: SHADER,
        },
    ],
};

/// (amplitude, decay) at the frame's severity: both linear between the table's rows, from
/// amplitude 0 (no fog) and the first row's decay at severity 0.
fn amplitude_decay(key: &FrameKey) -> (f32, f64) {
    let amplitude = key.interpolate(0.0, &AMPLITUDE_DECAY.map(|(a, _)| a));
    let decay = key.interpolate(AMPLITUDE_DECAY[0].1, &AMPLITUDE_DECAY.map(|(_, d)| d));
    (amplitude as f32, decay)
}

/// The plasma map's side for a frame: the next power of two of the larger side.
pub fn map_size(width: u32, height: u32) -> u32 {
    width.max(height).next_power_of_two()
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Level {
    key: [u32; 4],
    step: u32,
    size: u32,
    wibble: f32,
    _pad: f32,
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct FogParams {
    amplitude: f32,
    _pad: [f32; 3],
}

/// (step, wibble) of every level, coarsest first.
fn levels(size: u32, decay: f64) -> Vec<(u32, f32)> {
    let mut out = Vec::new();
    let (mut step, mut wibble) = (size, WIBBLE);
    while step >= 2 {
        out.push((step, wibble as f32));
        step /= 2;
        wibble /= decay;
    }
    out
}

struct LevelPasses {
    params: wgpu::Buffer,
    square: wgpu::BindGroup,
    diamond: wgpu::BindGroup,
}

struct Fog {
    square: wgpu::ComputePipeline,
    diamond: wgpu::ComputePipeline,
    range_pipeline: wgpu::ComputePipeline,
    levels: Vec<LevelPasses>,
    map: wgpu::Texture,
    range: wgpu::Buffer,
    /// `range` copied for the per-pixel pass (see `crate::perturbation::Kit::uniform_buffer`).
    range_uniform: wgpu::Buffer,
    pass: ColorPass,
    size: u32,
}

impl Fog {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        let size = map_size(kit.width, kit.height);
        let map = storage_texture(kit, "fog plasma", wgpu::TextureFormat::R32Float, size, size);
        let square = kit.pipeline_entry(PLASMA_SHADER, "square")?;
        let diamond = kit.pipeline_entry(PLASMA_SHADER, "diamond")?;
        let map_view = view(&map);
        let levels = (0..size.trailing_zeros())
            .map(|_| {
                let params = kit.uniform_buffer::<Level>("fog level");
                let resources = [
                    wgpu::BindingResource::TextureView(&map_view),
                    params.as_entire_binding(),
                ];
                LevelPasses {
                    square: kit.bind_group(&square, "fog square", &resources),
                    diamond: kit.bind_group(&diamond, "fog diamond", &resources),
                    params,
                }
            })
            .collect();
        Ok(Self {
            square,
            diamond,
            range_pipeline: kit.pipeline("perturb/image/fog_range.wgsl")?,
            levels,
            map,
            range: kit.storage_buffer("fog range", 16),
            range_uniform: kit.uniform_buffer::<[u32; 4]>("fog range"),
            pass: ColorPass::runs::<FogParams>(kit, SHADER)?,
            size,
        })
    }
}

impl GpuPerturbation for Fog {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        let (amplitude, decay) = amplitude_decay(key);
        let rng = key.rng(NAME, 0);
        for (passes, (step, wibble)) in self.levels.iter().zip(levels(self.size, decay)) {
            let level = Level {
                key: rng.0,
                step,
                size: self.size,
                wibble,
                _pad: 0.0,
            };
            kit.write_uniform(&passes.params, &level);
            let cells = self.size / step;
            kit.dispatch_grid(
                encoder,
                &self.square,
                &passes.square,
                "fog square",
                cells,
                cells,
            );
            kit.dispatch_grid(
                encoder,
                &self.diamond,
                &passes.diamond,
                "fog diamond",
                cells,
                cells,
            );
        }
        encoder.clear_buffer(&self.range, 0, None);
        let map = view(&self.map);
        let color = frame.color_view();
        let range = kit.bind_group(
            &self.range_pipeline,
            "fog range",
            &[
                wgpu::BindingResource::TextureView(&map),
                wgpu::BindingResource::TextureView(color),
                self.range.as_entire_binding(),
            ],
        );
        let (columns, rows) = (self.size.div_ceil(16), self.size);
        kit.dispatch_grid(
            encoder,
            &self.range_pipeline,
            &range,
            "fog range",
            columns,
            rows,
        );
        encoder.copy_buffer_to_buffer(&self.range, 0, &self.range_uniform, 0, None);
        let params = FogParams {
            amplitude,
            _pad: [0.0; 3],
        };
        let extra = [
            wgpu::BindingResource::TextureView(&map),
            self.range_uniform.as_entire_binding(),
        ];
        self.pass.encode(kit, encoder, frame, &params, &extra);
        Ok(())
    }
}

/// The plasma map (row-major, `size`²), unnormalised: the twin of `fog_plasma.wgsl`.
pub fn plasma(size: u32, decay: f64, rng: &RngKey) -> Vec<f32> {
    let n = size as usize;
    let mut map = vec![0.0f32; n * n];
    let at =
        |map: &[f32], x: u32, y: u32| map[((y & (size - 1)) * size + (x & (size - 1))) as usize];
    let mean = |sum: f32, x: u32, y: u32, w: f32| {
        let u = uniform(rng.draw([x, y, 0, 0])[0]);
        sum / 4.0 + w * ((2.0 * u - 1.0) * w)
    };
    for (s, w) in levels(size, decay) {
        let h = s / 2;
        let cells = size / s;
        for j in 0..cells {
            for i in 0..cells {
                let (x, y) = (i * s, j * s);
                let sum = if s == size {
                    0.0
                } else {
                    (at(&map, x, y) + at(&map, x, y + s))
                        + (at(&map, x + s, y) + at(&map, x + s, y + s))
                };
                map[((y + h) * size + x + h) as usize] = mean(sum, x + h, y + h, w);
            }
        }
        let mut new = Vec::with_capacity(2 * (cells * cells) as usize);
        for j in 0..cells {
            for i in 0..cells {
                let (x, y) = (i * s, j * s);
                let across = (at(&map, x + h, y + h) + at(&map, x + h, y + size - h))
                    + (at(&map, x, y) + at(&map, x + s, y));
                new.push(((x + h, y), mean(across, x + h, y, w)));
                let down = (at(&map, x + h, y + h) + at(&map, x + size - h, y + h))
                    + (at(&map, x, y) + at(&map, x, y + s));
                new.push(((x, y + h), mean(down, x, y + h, w)));
            }
        }
        for ((x, y), v) in new {
            map[(y * size + x) as usize] = v;
        }
    }
    map
}

/// CPU twin of fog.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let (amplitude, decay) = amplitude_decay(key);
    let size = map_size(image.width, image.height);
    let map = plasma(size, decay, &key.rng(NAME, 0));
    let high = map.iter().copied().fold(f32::MIN, f32::max);
    let low = map.iter().copied().fold(f32::MAX, f32::min);
    let brightest = image.data.iter().flatten().copied().fold(0.0, f32::max);
    let mut out = image.clone();
    for y in 0..image.height {
        for x in 0..image.width {
            let p = (map[(y * size + x) as usize] - low) / (high - low);
            let i = out.index(x, y);
            out.data[i] = image.data[i].map(|c| {
                store_truncated((c + amplitude * p) * brightest / (brightest + amplitude))
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn map_is_the_next_power_of_two() {
        assert_eq!(map_size(1200, 680), 2048);
        assert_eq!(map_size(640, 480), 1024);
        assert_eq!(map_size(64, 64), 64);
        assert_eq!(levels(2048, 2.0).len(), 11);
    }

    #[test]
    fn plasma_is_fractal_smooth_and_fills_every_point() {
        let rng = RngKey::new(3, NAME, 0, 0);
        let map = plasma(64, 2.0, &rng);
        assert_eq!(map[0], 0.0);
        // Neighbouring points differ far less than the map's range (a smooth fractal, not
        // white noise), and the map is not constant.
        let (high, low) = map
            .iter()
            .fold((f32::MIN, f32::MAX), |(h, l), &v| (h.max(v), l.min(v)));
        let mean_step = (0..63 * 64)
            .map(|i| (map[i + 64] - map[i]).abs())
            .sum::<f32>()
            / (63.0 * 64.0);
        assert!(high - low > 1000.0, "range {}", high - low);
        assert!(mean_step < 0.1 * (high - low), "step {mean_step}");
    }

    #[test]
    fn fog_lifts_dark_pixels_and_keeps_the_brightest_bounded() {
        let clean = RgbF32::from_rgb8(&testing::test_image(64, 48));
        let out = twin(&clean, &testing::key(1, 5));
        let mean =
            |img: &RgbF32| img.data.iter().flatten().sum::<f32>() / (3 * img.data.len()) as f32;
        // Black stays ≥ 0 and gets brighter on average; contrast falls.
        let black: Vec<usize> = (0..clean.data.len())
            .filter(|&i| clean.data[i] == [0.0; 3])
            .collect();
        let lifted = black.iter().map(|&i| out.data[i][0]).sum::<f32>() / black.len() as f32;
        assert!(lifted > 0.2, "black lifted to {lifted}");
        assert!(mean(&out) > mean(&clean) - 0.2);
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
