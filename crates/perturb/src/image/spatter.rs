//! spatter: imagecorruptions' `spatter`. A liquid layer of blurred Gaussian noise, cut at a
//! threshold, makes droplets. Water (severities 1–3) brightens them with pale turquoise shaded
//! like theirs: Canny edges of the layer → distance to the nearest edge (exact, truncated at
//! 20) → box blur → histogram equalisation → emboss → box blur, times the layer, normalised by
//! its maximum. Mud (4–5) pastes brown where the blurred droplet mask exceeds 0.8.
//! Differences from OpenCV, all small: Canny's hysteresis is one step (weak edges next to strong
//! ones survive), and distances are exact Euclidean instead of the 5×5 chamfer.

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use super::color_pass::ColorPass;
use super::kernels::{Edge, Kernel1dUniform};
use super::separable::{gaussian_runs, Channels, SeparableFilter};
use super::textures::storage_texture;
use crate::perturbation::{view, Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, RustLayout, UniformLayout};
use crate::PerturbError;

mod twin;
pub use twin::twin;

const NAME: &str = "spatter";
const WATER_SHADER: &str = "perturb/image/spatter.wgsl";
const MUD_SHADER: &str = "perturb/image/spatter_mud.wgsl";

/// Water or mud.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Liquid {
    Water,
    Mud,
}

/// (mean, std, blur σ, threshold, intensity, kind) per severity (docs/src/perturbations.md §3,
/// imagecorruptions `spatter`; for mud the "intensity" is the mask blur σ).
pub const PARAMS: [(f32, f32, f64, f32, f32, Liquid); 5] = [
    (0.65, 0.3, 4.0, 0.69, 0.6, Liquid::Water),
    (0.65, 0.3, 3.0, 0.68, 0.6, Liquid::Water),
    (0.65, 0.3, 2.0, 0.68, 0.5, Liquid::Water),
    (0.65, 0.3, 1.0, 0.65, 1.5, Liquid::Mud),
    (0.67, 0.4, 1.0, 0.65, 1.5, Liquid::Mud),
];

/// Pale turquoise (175, 238, 238) and mud brown (63, 42, 20), as imagecorruptions adds them.
pub const WATER_COLOR: [f32; 3] = [175.0 / 255.0, 238.0 / 255.0, 238.0 / 255.0];
pub const MUD_COLOR: [f32; 3] = [63.0 / 255.0, 42.0 / 255.0, 20.0 / 255.0];

/// SciPy's default truncation for skimage's `gaussian`.
const TRUNCATE: f64 = 4.0;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "spatter: water droplets (pale turquoise, embossed rims) or mud blobs",
    parameters: |s| {
        let (mean, std, sigma, threshold, intensity, kind) = PARAMS[s as usize - 1];
        match kind {
            Liquid::Water => format!(
                "water: noise N({mean}, {std}) blur σ={sigma} threshold={threshold} intensity={intensity}"
            ),
            Liquid::Mud => format!(
                "mud: noise N({mean}, {std}) blur σ={sigma} threshold={threshold} mask σ={intensity}"
            ),
        }
    },
    build: |kit| Ok(Box::new(Spatter::new(kit)?)),
    between: Between::WholeOnly("it turns from water (1-3) to mud (4-5)"),
    explicit: None,
    twin: Twin::Color(twin),
    // f32 noise, blur sums and shading; distances and equalisation are integer-exact.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[
        UniformLayout {
            rust: rust_layout!(Noise {
                key,
                mean,
                deviation
            }),
            wgsl: "Noise",
            shader: "perturb/image/spatter_noise.wgsl",
        },
        Kernel1dUniform::layout(Channels::One.shaders()[0]),
        Kernel1dUniform::layout(Channels::One.shaders()[1]),
        LiquidParams::layout("perturb/image/spatter_mud_mask.wgsl"),
        LiquidParams::layout("perturb/image/spatter_edges.wgsl"),
        LiquidParams::layout("perturb/image/spatter_shade.wgsl"),
        UniformLayout {
            rust: rust_layout!(Water { color, intensity }),
            wgsl: "Water",
            shader: WATER_SHADER,
        },
        UniformLayout {
            rust: rust_layout!(Mud { color }),
            wgsl: "Mud",
            shader: MUD_SHADER,
        },
    ],
};

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Noise {
    key: [u32; 4],
    mean: f32,
    deviation: f32,
    _pad: [f32; 2],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct LiquidParams {
    threshold: f32,
    _pad: [f32; 3],
}

impl LiquidParams {
    const LAYOUT: RustLayout = rust_layout!(LiquidParams { threshold });

    /// Its layout as `struct Liquid` (spatter_layer.wgsl) of `shader`.
    const fn layout(shader: &'static str) -> UniformLayout {
        UniformLayout {
            rust: Self::LAYOUT,
            wgsl: "Liquid",
            shader,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Water {
    color: [f32; 4],
    intensity: f32,
    _pad: [f32; 3],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Mud {
    color: [f32; 4],
}

struct Pipelines {
    noise: wgpu::ComputePipeline,
    mud_mask: wgpu::ComputePipeline,
    edges: wgpu::ComputePipeline,
    suppress: wgpu::ComputePipeline,
    seeds: wgpu::ComputePipeline,
    column_distance: wgpu::ComputePipeline,
    squared_distance: wgpu::ComputePipeline,
    distance: wgpu::ComputePipeline,
    equalize: wgpu::ComputePipeline,
    lut: wgpu::ComputePipeline,
    emboss: wgpu::ComputePipeline,
    shade: wgpu::ComputePipeline,
}

struct Spatter {
    pipelines: Pipelines,
    noise: wgpu::Buffer,
    threshold: wgpu::Buffer,
    /// The noise blur and the mud mask blur (each with its own kernel uniforms).
    liquid_blur: SeparableFilter,
    mask_blur: SeparableFilter,
    /// r32float: [noise / equalised / shade, edges / distance / embossed]
    planes: [wgpu::Texture; 2],
    /// r32float: the blurs' row pass, the blurred noise (for mud, then the blurred mask) and the
    /// mud mask
    rows: wgpu::Texture,
    blurred: wgpu::Texture,
    mud_mask: wgpu::Texture,
    /// r32uint: the liquid layer's Sobel gradient (x, y as 16-bit halves)
    gradient: wgpu::Texture,
    /// r32uint: edges, then squared distances (ping-pong)
    seeds: [wgpu::Texture; 2],
    histogram: wgpu::Buffer,
    lut: wgpu::Buffer,
    maximum: wgpu::Buffer,
    /// `lut` and `maximum` copied for the per-pixel passes (see `Kit::uniform_buffer`).
    lut_uniform: wgpu::Buffer,
    maximum_uniform: wgpu::Buffer,
    water: ColorPass,
    mud: ColorPass,
}

fn image_pipeline(kit: &Kit, pass: &str) -> Result<wgpu::ComputePipeline, PerturbError> {
    kit.pipeline(&format!("perturb/image/spatter_{pass}.wgsl"))
}

/// A pass in runs of 8 pixels of a row per invocation: `window_runs.wgsl`'s 3×3 windows and the
/// squared distance along rows.
fn dispatch_row_runs(
    kit: &Kit,
    encoder: &mut wgpu::CommandEncoder,
    pipeline: &wgpu::ComputePipeline,
    label: &str,
    resources: &[wgpu::BindingResource],
) {
    let bind_group = kit.bind_group(pipeline, label, resources);
    let runs = kit.width.div_ceil(8);
    kit.dispatch_grid(encoder, pipeline, &bind_group, label, runs, kit.height);
}

impl Spatter {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        let pipelines = Pipelines {
            noise: image_pipeline(kit, "noise")?,
            mud_mask: image_pipeline(kit, "mud_mask")?,
            edges: image_pipeline(kit, "edges")?,
            suppress: image_pipeline(kit, "suppress")?,
            seeds: image_pipeline(kit, "seeds")?,
            column_distance: image_pipeline(kit, "column_distance")?,
            squared_distance: image_pipeline(kit, "squared_distance")?,
            distance: image_pipeline(kit, "distance")?,
            equalize: image_pipeline(kit, "equalize")?,
            lut: image_pipeline(kit, "lut")?,
            emboss: image_pipeline(kit, "emboss")?,
            shade: image_pipeline(kit, "shade")?,
        };
        let texture = |label, format| storage_texture(kit, label, format, kit.width, kit.height);
        use wgpu::TextureFormat::{R32Float, R32Uint};
        Ok(Self {
            pipelines,
            noise: kit.uniform_buffer::<Noise>("spatter noise"),
            threshold: kit.uniform_buffer::<LiquidParams>("spatter threshold"),
            liquid_blur: SeparableFilter::new(kit, Channels::One)?,
            mask_blur: SeparableFilter::new(kit, Channels::One)?,
            planes: [
                texture("spatter noise", R32Float),
                texture("spatter work", R32Float),
            ],
            rows: texture("spatter rows", R32Float),
            blurred: texture("spatter blurred", R32Float),
            mud_mask: texture("spatter mud mask", R32Float),
            gradient: texture("spatter gradient", R32Uint),
            seeds: [
                texture("spatter seeds a", R32Uint),
                texture("spatter seeds b", R32Uint),
            ],
            histogram: kit.storage_buffer("spatter histogram", 256 * 4),
            lut: kit.storage_buffer("spatter equalisation", 256 * 4),
            maximum: kit.storage_buffer("spatter maximum", 16),
            lut_uniform: kit.uniform_buffer::<[u32; 256]>("spatter equalisation"),
            maximum_uniform: kit.uniform_buffer::<[u32; 4]>("spatter maximum"),
            water: ColorPass::runs::<Water>(kit, WATER_SHADER)?,
            mud: ColorPass::runs::<Mud>(kit, MUD_SHADER)?,
        })
    }

    /// Passes 5–15: shading from the liquid layer's edges, then the turquoise composite. The
    /// liquid layer is the blurred noise cut at the threshold, applied where it is read.
    fn encode_water(
        &self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        intensity: f32,
    ) {
        use wgpu::BindingResource::TextureView as T;
        let p = &self.pipelines;
        let [spare, work] = self.planes.each_ref().map(view);
        let blurred = view(&self.blurred);
        let liquid = self.threshold.as_entire_binding();
        let gradient = view(&self.gradient);
        let seeds = self.seeds.each_ref().map(view);
        dispatch_row_runs(
            kit,
            encoder,
            &p.edges,
            "spatter edges",
            &[T(&blurred), T(&gradient), liquid.clone()],
        );
        dispatch_row_runs(
            kit,
            encoder,
            &p.suppress,
            "spatter suppress",
            &[T(&gradient), T(&work)],
        );
        dispatch_row_runs(
            kit,
            encoder,
            &p.seeds,
            "spatter seeds",
            &[T(&work), T(&seeds[0])],
        );
        // Runs of 8 down columns, then along rows.
        let label = "spatter column distance";
        let columns = kit.bind_group(&p.column_distance, label, &[T(&seeds[0]), T(&seeds[1])]);
        let runs = kit.height.div_ceil(8);
        kit.dispatch_grid(
            encoder,
            &p.column_distance,
            &columns,
            label,
            kit.width,
            runs,
        );
        let resources = [T(&seeds[1]), T(&seeds[0])];
        let label = "spatter squared distance";
        dispatch_row_runs(kit, encoder, &p.squared_distance, label, &resources);
        let nearest = &seeds[0];
        encoder.clear_buffer(&self.histogram, 0, None);
        encoder.clear_buffer(&self.maximum, 0, None);
        let resources = [T(nearest), T(&work), self.histogram.as_entire_binding()];
        dispatch_row_runs(kit, encoder, &p.distance, "spatter distance", &resources);
        let resources = [
            self.histogram.as_entire_binding(),
            self.lut.as_entire_binding(),
        ];
        let equalize = kit.bind_group(&p.equalize, "spatter equalize", &resources);
        kit.dispatch_workgroups(
            encoder,
            &p.equalize,
            &equalize,
            "spatter equalize",
            [1, 1, 1],
        );
        encoder.copy_buffer_to_buffer(&self.lut, 0, &self.lut_uniform, 0, None);
        let resources = [T(&work), T(&spare), self.lut_uniform.as_entire_binding()];
        let lut = kit.bind_group(&p.lut, "spatter lut", &resources);
        kit.dispatch(encoder, &p.lut, &lut, "spatter lut");
        dispatch_row_runs(
            kit,
            encoder,
            &p.emboss,
            "spatter emboss",
            &[T(&spare), T(&work)],
        );
        let resources = [
            T(&work),
            T(&blurred),
            T(&spare),
            self.maximum.as_entire_binding(),
            liquid,
        ];
        dispatch_row_runs(kit, encoder, &p.shade, "spatter shade", &resources);
        let params = Water {
            color: [WATER_COLOR[0], WATER_COLOR[1], WATER_COLOR[2], 0.0],
            intensity,
            _pad: [0.0; 3],
        };
        encoder.copy_buffer_to_buffer(&self.maximum, 0, &self.maximum_uniform, 0, None);
        let extra = [T(&spare), self.maximum_uniform.as_entire_binding()];
        self.water.encode(kit, encoder, frame, &params, &extra);
    }
}

impl GpuPerturbation for Spatter {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        use wgpu::BindingResource::TextureView as T;
        let (mean, deviation, sigma, threshold, intensity, kind) = PARAMS[key.level()];
        let noise = Noise {
            key: key.rng(NAME, 0).0,
            mean,
            deviation,
            _pad: [0.0; 2],
        };
        kit.write_uniform(&self.noise, &noise);
        let liquid_params = LiquidParams {
            threshold,
            _pad: [0.0; 3],
        };
        kit.write_uniform(&self.threshold, &liquid_params);
        let blur = gaussian_runs(NAME, sigma, TRUNCATE, Edge::Replicate)?;
        self.liquid_blur.set_kernels(kit, &blur, &blur);
        let p = &self.pipelines;
        let noise_plane = view(&self.planes[0]);
        let rows = view(&self.rows);
        let (blurred, mud_mask) = (view(&self.blurred), view(&self.mud_mask));
        let resources = [T(&noise_plane), self.noise.as_entire_binding()];
        let bind_group = kit.bind_group(&p.noise, "spatter noise", &resources);
        kit.dispatch(encoder, &p.noise, &bind_group, "spatter noise");
        self.liquid_blur
            .encode(kit, encoder, &noise_plane, &rows, &blurred);
        match kind {
            Liquid::Water => self.encode_water(kit, encoder, frame, intensity),
            Liquid::Mud => {
                let resources = [
                    T(&blurred),
                    T(&mud_mask),
                    self.threshold.as_entire_binding(),
                ];
                let bind_group = kit.bind_group(&p.mud_mask, "spatter mud mask", &resources);
                kit.dispatch(encoder, &p.mud_mask, &bind_group, "spatter mud mask");
                let mask = gaussian_runs(NAME, intensity as f64, TRUNCATE, Edge::Replicate)?;
                self.mask_blur.set_kernels(kit, &mask, &mask);
                self.mask_blur
                    .encode(kit, encoder, &mud_mask, &rows, &blurred);
                let params = Mud {
                    color: [MUD_COLOR[0], MUD_COLOR[1], MUD_COLOR[2], 0.0],
                };
                self.mud
                    .encode(kit, encoder, frame, &params, &[T(&blurred)]);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn seeded() {
        let clean = testing::test_image(64, 48);
        for severity in [1, 5] {
            let a = testing::run_color(&ENTRY, severity, 1, &clean);
            let b = testing::run_color(&ENTRY, severity, 1, &clean);
            let c = testing::run_color(&ENTRY, severity, 2, &clean);
            assert_eq!(a.data, b.data);
            assert_ne!(a.data, c.data);
        }
    }
}
