//! snow: imagecorruptions' `snow`: a Gaussian noise layer, centre-zoomed, thresholded and
//! motion-blurred at an angle in [−135°, −45°) per frame, rounded to 8 bits; the image is
//! lightened toward max(x, 1.5·gray + 0.5) by (1 − blend) and the layer is added twice (as is
//! and rotated by 180°).

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use super::color_pass::ColorPass;
use super::kernels::{apply_line_taps, motion_line_taps, LineKernelUniform, LineTap};
use super::motion_blur::frame_angle;
use super::textures::storage_texture;
use super::zoom_blur::{axis_window, AxisWindow};
use crate::image_f32::RgbF32;
use crate::perturbation::{view, Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::rng::{normal_pair, RngKey};
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, UniformLayout};
use crate::PerturbError;

const NAME: &str = "snow";
const NOISE_SHADER: &str = "perturb/image/snow_noise.wgsl";
const LAYER_SHADER: &str = "perturb/image/snow_layer.wgsl";
const SHADER: &str = "perturb/image/snow.wgsl";

/// One severity of snow (docs/src/perturbations.md §3, imagecorruptions `snow`).
#[derive(Clone, Copy, Debug)]
pub struct SnowParams {
    pub mean: f32,
    pub std: f32,
    pub zoom: f64,
    pub threshold: f32,
    pub blur_radius: u32,
    pub blur_sigma: f64,
    pub blend: f32,
}

const fn snow(
    mean: f32,
    zoom: f64,
    threshold: f32,
    radius: u32,
    sigma: f64,
    blend: f32,
) -> SnowParams {
    SnowParams {
        mean,
        std: 0.3,
        zoom,
        threshold,
        blur_radius: radius,
        blur_sigma: sigma,
        blend,
    }
}

pub const PARAMS: [SnowParams; 5] = [
    snow(0.1, 3.0, 0.5, 10, 4.0, 0.8),
    snow(0.2, 2.0, 0.5, 12, 4.0, 0.7),
    snow(0.55, 4.0, 0.9, 12, 8.0, 0.7),
    snow(0.55, 4.5, 0.85, 12, 8.0, 0.65),
    snow(0.55, 2.5, 0.85, 12, 12.0, 0.55),
];

/// The flakes fall at an angle uniform in [−135°, −45°) per frame.
const ANGLE_RANGE: (f64, f64) = (-135.0, -45.0);

/// Extra rows and columns of the zoomed layer beyond the frame: round(ceil(n/z)·z) − n < z.
const LAYER_MARGIN: u32 = 8;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "snow: zoomed, thresholded, motion-blurred noise flakes over a lightened image",
    parameters: |s| {
        let p = PARAMS[s as usize - 1];
        format!(
            "noise N({}, {}) zoom={} threshold={} blur radius={} σ={} blend={}",
            p.mean, p.std, p.zoom, p.threshold, p.blur_radius, p.blur_sigma, p.blend
        )
    },
    build: |kit| Ok(Box::new(Snow::new(kit)?)),
    between: Between::WholeOnly(
        "its flake zoom goes 3, 2, 4, 4.5, 2.5: no parameter path between the rows",
    ),
    explicit: None,
    twin: Twin::Color(twin),
    // f32 Box-Muller noise, bilinear zoom and blur sums in another order.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[
        UniformLayout {
            rust: rust_layout!(NoiseUniform {
                key,
                origin,
                grid,
                extent,
                mean,
                deviation
            }),
            wgsl: "Noise",
            shader: NOISE_SHADER,
        },
        UniformLayout {
            rust: rust_layout!(LayerUniform {
                window,
                zoomed,
                origin,
                threshold
            }),
            wgsl: "Layer",
            shader: LAYER_SHADER,
        },
        UniformLayout {
            rust: rust_layout!(Composite { zoomed, blend }),
            wgsl: "Snow",
            shader: SHADER,
        },
        LineKernelUniform::layout(SHADER),
    ],
};

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct NoiseUniform {
    key: [u32; 4],
    origin: [u32; 2],
    grid: [u32; 2],
    extent: [u32; 2],
    mean: f32,
    deviation: f32,
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct LayerUniform {
    window: [f32; 4],
    zoomed: [u32; 2],
    origin: [i32; 2],
    threshold: f32,
    _pad: [f32; 3],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Composite {
    zoomed: [i32; 2],
    blend: f32,
    _pad: f32,
}

/// Everything one frame of snow needs, computed on the CPU.
struct FramePlan {
    x: AxisWindow,
    y: AxisWindow,
    taps: Vec<LineTap>,
    noise: RngKey,
}

fn plan(p: &SnowParams, seed: u64, frame: u32, width: u32, height: u32) -> FramePlan {
    let (x, y) = (axis_window(width, p.zoom), axis_window(height, p.zoom));
    let angle = frame_angle(RngKey::new(seed, NAME, frame, 1), ANGLE_RANGE);
    FramePlan {
        x,
        y,
        taps: motion_line_taps(p.blur_radius, p.blur_sigma, angle, x.zoomed, y.zoomed),
        noise: RngKey::new(seed, NAME, frame, 0),
    }
}

struct Snow {
    noise_pipeline: wgpu::ComputePipeline,
    noise_params: wgpu::Buffer,
    layer_pipeline: wgpu::ComputePipeline,
    layer_params: wgpu::Buffer,
    line: wgpu::Buffer,
    /// The noise at the grid cells the zoom reads (at most the frame and one cell more).
    cells: wgpu::Texture,
    layer: wgpu::Texture,
    pass: ColorPass,
}

impl Snow {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        let (w, h) = (kit.width + LAYER_MARGIN, kit.height + LAYER_MARGIN);
        let cells = storage_texture(
            kit,
            "snow noise",
            wgpu::TextureFormat::R32Float,
            kit.width + 1,
            kit.height + 1,
        );
        Ok(Self {
            noise_pipeline: kit.pipeline(NOISE_SHADER)?,
            noise_params: kit.uniform_buffer::<NoiseUniform>("snow noise"),
            cells,
            layer_pipeline: kit.pipeline(LAYER_SHADER)?,
            layer_params: kit.uniform_buffer::<LayerUniform>("snow layer"),
            line: kit.uniform_buffer::<LineKernelUniform>("snow blur"),
            layer: storage_texture(kit, "snow layer", wgpu::TextureFormat::R32Float, w, h),
            pass: ColorPass::mirrored_runs::<Composite>(kit, SHADER)?,
        })
    }
}

impl GpuPerturbation for Snow {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        let p = PARAMS[key.level()];
        let plan = plan(&p, key.seed, key.frame, kit.width, kit.height);
        let line = LineKernelUniform::new(&plan.taps).ok_or_else(|| PerturbError::Unsupported {
            name: NAME.into(),
            message: format!("{} blur taps do not fit the shader", plan.taps.len()),
        })?;
        kit.write_uniform(&self.line, &line);
        let origin = [plan.x.top as u32, plan.y.top as u32];
        let extent = [plan.x.crop + 1, plan.y.crop + 1];
        let noise = NoiseUniform {
            key: plan.noise.0,
            origin,
            grid: [kit.width, kit.height],
            extent,
            mean: p.mean,
            deviation: p.std,
        };
        kit.write_uniform(&self.noise_params, &noise);
        let cells = view(&self.cells);
        let resources = [
            wgpu::BindingResource::TextureView(&cells),
            self.noise_params.as_entire_binding(),
        ];
        let bind_group = kit.bind_group(&self.noise_pipeline, "snow noise", &resources);
        let label = "snow noise";
        kit.dispatch_grid(
            encoder,
            &self.noise_pipeline,
            &bind_group,
            label,
            extent[0],
            extent[1],
        );
        let layer = LayerUniform {
            window: [plan.x.top, plan.y.top, plan.x.scale, plan.y.scale],
            zoomed: [plan.x.zoomed, plan.y.zoomed],
            origin: origin.map(|o| o as i32),
            threshold: p.threshold,
            _pad: [0.0; 3],
        };
        kit.write_uniform(&self.layer_params, &layer);
        let layer_view = view(&self.layer);
        let bind_group = kit.bind_group(
            &self.layer_pipeline,
            "snow layer",
            &[
                wgpu::BindingResource::TextureView(&layer_view),
                self.layer_params.as_entire_binding(),
                wgpu::BindingResource::TextureView(&cells),
            ],
        );
        let (zw, zh) = (plan.x.zoomed, plan.y.zoomed);
        kit.dispatch_grid(
            encoder,
            &self.layer_pipeline,
            &bind_group,
            "snow layer",
            zw,
            zh,
        );
        let composite = Composite {
            zoomed: [zw as i32, zh as i32],
            blend: p.blend,
            _pad: 0.0,
        };
        let extra = [
            wgpu::BindingResource::TextureView(&layer_view),
            self.line.as_entire_binding(),
        ];
        self.pass.encode(kit, encoder, frame, &composite, &extra);
        Ok(())
    }
}

/// The snow layer after the blur and rounding, `zoomed.x × zoomed.y` (twin of both passes'
/// layer work).
fn layer_twin(p: &SnowParams, plan: &FramePlan, width: u32, height: u32) -> Vec<f32> {
    let noise = |x: i64, y: i64| {
        let (x, y) = (
            x.clamp(0, width as i64 - 1) as u32,
            y.clamp(0, height as i64 - 1) as u32,
        );
        let bits = plan.noise.draw([x, y, 0, 0]);
        p.mean + p.std * normal_pair(bits[0], bits[1])[0]
    };
    let mix = |a: f32, b: f32, t: f32| a * (1.0 - t) + b * t;
    let (zw, zh) = (plan.x.zoomed, plan.y.zoomed);
    let mut layer = Vec::with_capacity((zw * zh) as usize);
    for y in 0..zh {
        for x in 0..zw {
            let ax = plan.x.top + x as f32 * plan.x.scale;
            let ay = plan.y.top + y as f32 * plan.y.scale;
            let (bx, by) = (ax.floor(), ay.floor());
            let (fx, fy) = (ax - bx, ay - by);
            let (qx, qy) = (bx as i64, by as i64);
            let upper = mix(noise(qx, qy), noise(qx + 1, qy), fx);
            let lower = mix(noise(qx, qy + 1), noise(qx + 1, qy + 1), fx);
            let v = mix(upper, lower, fy);
            layer.push(if v < p.threshold {
                0.0
            } else {
                v.clamp(0.0, 1.0)
            });
        }
    }
    apply_line_taps(&layer, zw, zh, &plan.taps)
        .into_iter()
        .map(|v| (v * 255.0).round_ties_even() / 255.0)
        .collect()
}

/// CPU twin of snow.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let p = PARAMS[key.level()];
    let (w, h) = (image.width, image.height);
    let plan = plan(&p, key.seed, key.frame, w, h);
    let layer = layer_twin(&p, &plan, w, h);
    let zw = plan.x.zoomed;
    let at = |x: u32, y: u32| layer[(y * zw + x) as usize];
    let mut out = image.clone();
    for y in 0..h {
        for x in 0..w {
            let i = out.index(x, y);
            let c = image.data[i];
            let gray = c[0] * 0.299 + c[1] * 0.587 + c[2] * 0.114;
            let flakes = at(x, y) + at(w - 1 - x, h - 1 - y);
            out.data[i] = c.map(|v| {
                let lightened = p.blend * v + (1.0 - p.blend) * v.max(gray * 1.5 + 0.5);
                crate::image_f32::truncate8(lightened + flakes) as f32 / 255.0
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
    fn flakes_cover_a_plausible_fraction_and_streak_downwards() {
        // Severity 3: N(0.55, 0.3) thresholded at 0.9 keeps ~12% of the (zoomed) noise, the
        // blur spreads it; the layer is sparse but not empty.
        let p = PARAMS[2];
        let plan = plan(&p, 2, 0, 160, 120);
        let layer = layer_twin(&p, &plan, 160, 120);
        let lit = layer.iter().filter(|&&v| v > 0.0).count() as f32 / layer.len() as f32;
        assert!((0.05..0.8).contains(&lit), "lit fraction {lit}");
        // Angles in [−135°, −45°): every tap moves up (dy ≤ 0) and more in y than in x.
        for t in &plan.taps {
            assert!(t.dy <= 0 && t.dx.abs() <= t.dy.abs(), "{t:?}");
        }
    }

    #[test]
    fn seeded() {
        let clean = testing::test_image(64, 48);
        let a = testing::run_color(&ENTRY, 2, 1, &clean);
        let b = testing::run_color(&ENTRY, 2, 1, &clean);
        let c = testing::run_color(&ENTRY, 2, 2, &clean);
        assert_eq!(a.data, b.data);
        assert_ne!(a.data, c.data);
    }
}
