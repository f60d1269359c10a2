//! pixelate: PIL `resize(BOX)` down by c, then `resize(NEAREST)` back up, as imagecorruptions'
//! `pixelate`, reproduced to the bit: PIL's BOX takes the unweighted mean of the pixels whose
//! centres fall in each output box (its support rule, not an area-weighted mean), in 8-bit
//! fixed point, rows first; its NEAREST steps the source position by repeated f64 addition.

use bytemuck::{Pod, Zeroable};
use rslam_core::RgbImage;
use rslam_gpu::FrameTextures;

use crate::perturbation::{view, Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::severity::Severity;
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, UniformLayout};
use crate::PerturbError;

const SHADER: &str = "perturb/image/pixelate.wgsl";

/// Scale per severity (docs/src/perturbations.md §3, imagecorruptions `pixelate`).
pub const SCALE: [f64; 5] = [0.6, 0.5, 0.4, 0.3, 0.25];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: "pixelate",
    group: Group::Image,
    description: "box-average down by the scale, nearest-neighbour back up (PIL BOX + NEAREST)",
    parameters: |s| format!("scale={}", SCALE[s as usize - 1]),
    build: |kit| Ok(Box::new(Pixelate::new(kit)?)),
    between: Between::Interpolated("scale linear from 1"),
    explicit: None,
    twin: Twin::Color8(twin),
    // PIL's fixed-point integer arithmetic on both sides.
    twin_tolerance: Tolerance::EXACT,
    uniforms: &[UniformLayout {
        rust: rust_layout!(Params { sizes }),
        wgsl: "Params",
        shader: SHADER,
    }],
};

/// The scale at the frame's severity: linear between the table's rows, from 1 at severity 0.
fn scale(key: &FrameKey) -> f64 {
    key.interpolate(1.0, &SCALE)
}

/// PIL's fixed-point precision for 8-bit resampling.
const PRECISION_BITS: u32 = 22;

/// One axis of PIL's BOX resample: for each output index, the input run (start, count).
pub fn box_runs(input: u32, output: u32) -> Vec<(u32, u32)> {
    let scale = input as f64 / output as f64;
    let support = 0.5 * scale.max(1.0);
    (0..output)
        .map(|xx| {
            let center = (xx as f64 + 0.5) * scale;
            let xmin = ((center - support + 0.5) as i64).max(0) as u32;
            let xmax = ((center + support + 0.5) as i64).min(input as i64) as u32;
            let inside = |x: u32| {
                let t = (x as f64 - center + 0.5) / scale.max(1.0);
                t > -0.5 && t <= 0.5
            };
            let first = (xmin..xmax).find(|&x| inside(x)).unwrap_or(xmin);
            let count = (first..xmax).take_while(|&x| inside(x)).count() as u32;
            (first, count.max(1))
        })
        .collect()
}

/// One axis of PIL's NEAREST resize from `input` up to `output` (ImagingScaleAffine: the
/// source position starts at scale/2 and grows by repeated addition of scale).
pub fn nearest_index(input: u32, output: u32) -> Vec<u32> {
    let step = input as f64 / output as f64;
    let mut position = 0.5 * step;
    (0..output)
        .map(|_| {
            let index = (position as u32).min(input - 1);
            position += step;
            index
        })
        .collect()
}

/// PIL's `clip8` of a mean with coefficient (int)(0.5 + 2^22 / n).
fn box_average(sum: u32, count: u32) -> u8 {
    let weight = ((1u32 << (PRECISION_BITS + 1)) + count) / (2 * count);
    (((1u32 << (PRECISION_BITS - 1)) + sum * weight) >> PRECISION_BITS).min(255) as u8
}

/// The tables of one severity.
struct Plan {
    small: [u32; 2],
    tables: Vec<u32>,
}

fn small_size(width: u32, height: u32, scale: f64) -> [u32; 2] {
    [
        (width as f64 * scale) as u32,
        (height as f64 * scale) as u32,
    ]
}

/// For each small index, the run (start, count) of large indices whose nearest source it is
/// (`nearest_index` is non-decreasing and, when upscaling, visits every small index).
fn nearest_blocks(small: u32, large: u32) -> Vec<(u32, u32)> {
    let mut blocks = vec![(0, 0); small as usize];
    for (x, s) in nearest_index(small, large).into_iter().enumerate() {
        let block = &mut blocks[s as usize];
        if block.1 == 0 {
            block.0 = x as u32;
        }
        block.1 += 1;
    }
    blocks
}

impl Plan {
    fn new(width: u32, height: u32, scale: f64) -> Self {
        let small = small_size(width, height, scale);
        let pack = |(start, count): (u32, u32)| start | (count << 16);
        let mut tables: Vec<u32> = box_runs(width, small[0]).into_iter().map(pack).collect();
        tables.extend(box_runs(height, small[1]).into_iter().map(pack));
        tables.extend(nearest_blocks(small[0], width).into_iter().map(pack));
        tables.extend(nearest_blocks(small[1], height).into_iter().map(pack));
        Self { small, tables }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Params {
    sizes: [u32; 4],
}

struct Pixelate {
    rows: wgpu::ComputePipeline,
    columns: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    tables: wgpu::Buffer,
    intermediate: wgpu::Texture,
    plans: Vec<Plan>,
    /// The plan of the last real severity, kept while frames keep it.
    between: Option<(Severity, Plan)>,
}

impl Pixelate {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        let smallest = small_size(kit.width, kit.height, SCALE[4]);
        if smallest.contains(&0) || kit.width > 0xffff || kit.height > 0xffff {
            return Err(PerturbError::Unsupported {
                name: ENTRY.name.into(),
                message: format!(
                    "needs frames of 4x4 to 65535x65535 pixels, got {}x{}",
                    kit.width, kit.height
                ),
            });
        }
        let plans: Vec<Plan> = SCALE
            .iter()
            .map(|&s| Plan::new(kit.width, kit.height, s))
            .collect();
        // Real severities below 1 shrink less than severity 1 does, down to scale 1.
        let largest = 2 * (kit.width + kit.height);
        let widest = kit.width;
        Ok(Self {
            rows: kit.pipeline_entry(SHADER, "box_rows")?,
            columns: kit.pipeline(SHADER)?,
            params: kit.uniform_buffer::<Params>(SHADER),
            tables: kit.storage_buffer(SHADER, largest as u64 * 4),
            intermediate: kit.ctx.storage_texture(
                "pixelate rows",
                wgpu::TextureFormat::Rgba8Unorm,
                (widest, kit.height),
            ),
            plans,
            between: None,
        })
    }
}

impl GpuPerturbation for Pixelate {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        let plan = match key.severity.as_whole() {
            Some(_) => &self.plans[key.level()],
            None => {
                if self.between.as_ref().map(|(s, _)| *s) != Some(key.severity) {
                    let plan = Plan::new(kit.width, kit.height, scale(key));
                    self.between = Some((key.severity, plan));
                }
                &self.between.as_ref().expect("made above").1
            }
        };
        let params = Params {
            sizes: [plan.small[0], plan.small[1], kit.width, kit.height],
        };
        kit.write_uniform(&self.params, &params);
        kit.ctx
            .queue
            .write_buffer(&self.tables, 0, bytemuck::cast_slice(&plan.tables));
        let frame_view = frame.color_view();
        let intermediate = view(&self.intermediate);
        let rows = kit.bind_group(
            &self.rows,
            SHADER,
            &[
                wgpu::BindingResource::TextureView(frame_view),
                wgpu::BindingResource::TextureView(&intermediate),
                self.params.as_entire_binding(),
                self.tables.as_entire_binding(),
            ],
        );
        kit.dispatch_grid(
            encoder,
            &self.rows,
            &rows,
            SHADER,
            plan.small[0],
            kit.height,
        );
        let columns = kit.bind_group(
            &self.columns,
            SHADER,
            &[
                wgpu::BindingResource::TextureView(&intermediate),
                wgpu::BindingResource::TextureView(frame_view),
                self.params.as_entire_binding(),
                self.tables.as_entire_binding(),
            ],
        );
        kit.dispatch_grid(
            encoder,
            &self.columns,
            &columns,
            SHADER,
            plan.small[0],
            plan.small[1],
        );
        Ok(())
    }
}

/// CPU twin: PIL's BOX down (rows, then columns, each rounded to 8 bits) and NEAREST up.
pub fn twin(image: &RgbImage, key: &FrameKey) -> RgbImage {
    let (w, h) = (image.width, image.height);
    let [sw, sh] = small_size(w, h, scale(key));
    let columns = box_runs(w, sw);
    let rows = box_runs(h, sh);
    let mut horizontal = vec![[0u8; 3]; (sw * h) as usize];
    for y in 0..h {
        for (sx, &(start, count)) in columns.iter().enumerate() {
            horizontal[(y * sw) as usize + sx] = std::array::from_fn(|c| {
                let sum = (start..start + count)
                    .map(|x| image.pixel(x, y)[c] as u32)
                    .sum();
                box_average(sum, count)
            });
        }
    }
    let xs = nearest_index(sw, w);
    let ys = nearest_index(sh, h);
    let mut out = RgbImage::new(w, h);
    for y in 0..h {
        let (start, count) = rows[ys[y as usize] as usize];
        for x in 0..w {
            let sx = xs[x as usize];
            let i = ((y * w + x) * 3) as usize;
            for (c, value) in out.data[i..i + 3].iter_mut().enumerate() {
                let sum = (start..start + count)
                    .map(|r| horizontal[(r * sw + sx) as usize][c] as u32)
                    .sum();
                *value = box_average(sum, count);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    /// Hand-checked against Pillow 13: `Image.resize((4, 1), BOX)` of 10 pixels takes runs
    /// [0,3) [3,5) [5,8) [8,10) (scale 2.5: centres 1.25, 3.75, 6.25, 8.75).
    #[test]
    fn box_runs_follow_pil_support() {
        assert_eq!(box_runs(10, 4), vec![(0, 3), (3, 2), (5, 3), (8, 2)]);
        assert_eq!(box_runs(8, 4), vec![(0, 2), (2, 2), (4, 2), (6, 2)]);
    }

    /// Pillow 13's `resize((1200, 1), NEAREST)` of 480 pixels: at x = 7 the exact position
    /// (7 + 0.5)·0.4 = 3 but PIL's accumulated f64 position lands just below, on 2.
    #[test]
    fn nearest_index_accumulates_like_pil() {
        let index = nearest_index(480, 1200);
        assert_eq!(&index[..12], &[0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 4, 4]);
        assert_eq!(index[1199], 479);
    }

    #[test]
    fn flat_image_stays_flat() {
        let grey = testing::uniform_image(50, 40, 77);
        for severity in 1..=5 {
            assert_eq!(twin(&grey, &testing::key(0, severity)), grey);
        }
    }
}
