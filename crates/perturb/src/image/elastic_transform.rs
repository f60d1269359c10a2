//! elastic_transform: the size-generic `elastic_transform` of imagecorruptions: two fields of
//! uniform noise in ±0.005·H, smoothed by a Gaussian of σ = 0.01·(H, W) (truncate 3, reflected
//! edges), scaled by α, displace the image, resampled bilinearly with reflected edges.

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use super::color_pass::ColorPass;
use super::kernels::{gaussian_half_kernel, symmetric_filter, Axis, Edge, Kernel1dUniform};
use super::separable::{gaussian_runs, Channels, SeparableFilter};
use crate::image_f32::RgbF32;
use crate::perturbation::{view, Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::rng::{uniform, RngKey};
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, UniformLayout};
use crate::PerturbError;

const NAME: &str = "elastic_transform";
const NOISE_SHADER: &str = "perturb/image/elastic_transform_noise.wgsl";
const WARP_SHADER: &str = "perturb/image/elastic_transform.wgsl";
/// The x and y displacement fields.
const FIELDS: Channels = Channels::Two;

/// α per severity: 250 × (0.05, 0.065, 0.085, 0.1, 0.12) (docs/src/perturbations.md §3, imagecorruptions).
pub const ALPHA: [f32; 5] = [12.5, 16.25, 21.25, 25.0, 30.0];

/// σ of the smoothing, as a fraction of the image height (rows) and width (columns).
const SIGMA_FRACTION: f64 = 0.01;
/// Noise amplitude as a fraction of the image height (both fields).
const AMPLITUDE_FRACTION: f32 = 0.005;
/// `gaussian(..., truncate=3)`.
const TRUNCATE: f64 = 3.0;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "elastic warp: smoothed random displacement field (σ = 1% of the frame size)",
    parameters: |s| {
        format!(
            "α={} σ=0.01·(H,W) amplitude ±0.005·H",
            ALPHA[s as usize - 1]
        )
    },
    build: |kit| Ok(Box::new(ElasticTransform::new(kit)?)),
    between: Between::Interpolated("α linear from 0"),
    explicit: None,
    twin: Twin::Color(twin),
    // f32 smoothing sums in another order move the sample point by ulps; bilinear weights.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[
        UniformLayout {
            rust: rust_layout!(Noise { key, amplitude }),
            wgsl: "Noise",
            shader: NOISE_SHADER,
        },
        Kernel1dUniform::layout(FIELDS.shaders()[0]),
        Kernel1dUniform::layout(FIELDS.shaders()[1]),
        UniformLayout {
            rust: rust_layout!(Warp { alpha }),
            wgsl: "Warp",
            shader: WARP_SHADER,
        },
    ],
};

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Noise {
    key: [u32; 4],
    amplitude: f32,
    _pad: [f32; 3],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Warp {
    alpha: f32,
    _pad: [f32; 3],
}

/// Half kernels along rows (σ = 0.01·W) and columns (σ = 0.01·H).
fn kernels(width: u32, height: u32) -> (Vec<f32>, Vec<f32>) {
    (
        gaussian_half_kernel(SIGMA_FRACTION * width as f64, TRUNCATE),
        gaussian_half_kernel(SIGMA_FRACTION * height as f64, TRUNCATE),
    )
}

/// The two noise values (for dx, dy) at a pixel: the twin of `elastic_transform_noise.wgsl`.
fn field_noise(rng: &RngKey, x: u32, y: u32, amplitude: f32) -> [f32; 2] {
    let bits = rng.draw([x, y, 0, 0]);
    [bits[0], bits[1]].map(|b| (2.0 * uniform(b) - 1.0) * amplitude)
}

struct ElasticTransform {
    noise_pipeline: wgpu::ComputePipeline,
    noise: wgpu::Buffer,
    smooth: SeparableFilter,
    warp: ColorPass,
    /// Noise, then the smoothed fields.
    fields: wgpu::Texture,
    intermediate: wgpu::Texture,
}

impl ElasticTransform {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        let (w, h) = (kit.width as f64, kit.height as f64);
        let rows = gaussian_runs(NAME, SIGMA_FRACTION * w, TRUNCATE, Edge::Reflect)?;
        let columns = gaussian_runs(NAME, SIGMA_FRACTION * h, TRUNCATE, Edge::Reflect)?;
        let smooth = SeparableFilter::new(kit, FIELDS)?;
        smooth.set_kernels(kit, &rows, &columns);
        Ok(Self {
            noise_pipeline: kit.pipeline(NOISE_SHADER)?,
            noise: kit.uniform_buffer::<Noise>("elastic noise"),
            smooth,
            warp: ColorPass::runs::<Warp>(kit, WARP_SHADER)?,
            fields: FIELDS.frame_texture(kit, "elastic displacement"),
            intermediate: FIELDS.frame_texture(kit, "elastic rows"),
        })
    }
}

impl GpuPerturbation for ElasticTransform {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        let noise = Noise {
            key: key.rng(NAME, 0).0,
            amplitude: AMPLITUDE_FRACTION * kit.height as f32,
            _pad: [0.0; 3],
        };
        kit.write_uniform(&self.noise, &noise);
        let (fields, intermediate) = (view(&self.fields), view(&self.intermediate));
        let bind_group = kit.bind_group(
            &self.noise_pipeline,
            "elastic noise",
            &[
                wgpu::BindingResource::TextureView(&fields),
                self.noise.as_entire_binding(),
            ],
        );
        kit.dispatch(encoder, &self.noise_pipeline, &bind_group, "elastic noise");
        self.smooth
            .encode(kit, encoder, &fields, &intermediate, &fields);
        let warp = Warp {
            alpha: key.interpolate(0.0, &ALPHA) as f32,
            _pad: [0.0; 3],
        };
        let extra = [wgpu::BindingResource::TextureView(&fields)];
        self.warp.encode(kit, encoder, frame, &warp, &extra);
        Ok(())
    }
}

/// The displacement (dx, dy) per pixel of the frame `key` names.
pub fn displacement(width: u32, height: u32, key: &FrameKey) -> Vec<[f32; 2]> {
    let rng = key.rng(NAME, 0);
    let amplitude = AMPLITUDE_FRACTION * height as f32;
    let noise: Vec<[f32; 2]> = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| field_noise(&rng, x, y, amplitude))
        .collect();
    let (row_half, column_half) = kernels(width, height);
    let alpha = key.interpolate(0.0, &ALPHA) as f32;
    let split = |c: usize| noise.iter().map(|n| n[c]).collect::<Vec<f32>>();
    let smooth = |plane: Vec<f32>| {
        let rows = symmetric_filter(&plane, width, height, &row_half, Axis::Rows, Edge::Reflect);
        symmetric_filter(
            &rows,
            width,
            height,
            &column_half,
            Axis::Columns,
            Edge::Reflect,
        )
    };
    let (dx, dy) = (smooth(split(0)), smooth(split(1)));
    dx.iter()
        .zip(&dy)
        .map(|(x, y)| [alpha * x, alpha * y])
        .collect()
}

/// CPU twin of elastic_transform.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let (w, h) = (image.width, image.height);
    let field = displacement(w, h, key);
    let pixel = |x: i64, y: i64| {
        image.at(
            Edge::Reflect.index(x, w as i64) as u32,
            Edge::Reflect.index(y, h as i64) as u32,
        )
    };
    let mut out = image.clone();
    for y in 0..h {
        for x in 0..w {
            let i = out.index(x, y);
            let (ax, ay) = (x as f32 + field[i][0], y as f32 + field[i][1]);
            let (bx, by) = (ax.floor(), ay.floor());
            let (fx, fy) = (ax - bx, ay - by);
            let (qx, qy) = (bx as i64, by as i64);
            let mix = |a: f32, b: f32, t: f32| a * (1.0 - t) + b * t;
            let (p00, p10) = (pixel(qx, qy), pixel(qx + 1, qy));
            let (p01, p11) = (pixel(qx, qy + 1), pixel(qx + 1, qy + 1));
            out.data[i] = std::array::from_fn(|c| {
                let upper = mix(p00[c], p10[c], fx);
                let lower = mix(p01[c], p11[c], fx);
                (crate::image_f32::truncate8(mix(upper, lower, fy)) as f32) / 255.0
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
    fn displacement_has_the_expected_spread() {
        // Uniform noise of half-width A has variance A²/3; a separable Gaussian of σ (σy, σx)
        // scales it by Σw² per axis ≈ 1/(2√π σ). For 200×160: A = 0.8, σ = (1.6, 2).
        let (w, h) = (200, 160);
        let field = displacement(w, h, &testing::key(11, 5));
        let n = field.len() as f64;
        let mean = field.iter().map(|d| d[0] as f64).sum::<f64>() / n;
        let var = field
            .iter()
            .map(|d| (d[0] as f64 - mean).powi(2))
            .sum::<f64>()
            / n;
        let (rows, columns) = kernels(w, h);
        let energy = |half: &[f32]| {
            half[0].powi(2) as f64 + 2.0 * half[1..].iter().map(|v| v.powi(2) as f64).sum::<f64>()
        };
        let a = (AMPLITUDE_FRACTION * h as f32) as f64;
        let expected = a * a / 3.0 * energy(&rows) * energy(&columns) * (ALPHA[4] as f64).powi(2);
        assert!(
            (var / expected - 1.0).abs() < 0.25,
            "variance {var}, expected {expected}"
        );
        assert!(mean.abs() < 0.2 * expected.sqrt(), "mean {mean}");
    }

    #[test]
    fn seeded() {
        let clean = testing::test_image(64, 48);
        let a = testing::run_color(&ENTRY, 5, 1, &clean);
        let b = testing::run_color(&ENTRY, 5, 1, &clean);
        let c = testing::run_color(&ENTRY, 5, 2, &clean);
        assert_eq!(a.data, b.data);
        assert_ne!(a.data, c.data);
    }
}
