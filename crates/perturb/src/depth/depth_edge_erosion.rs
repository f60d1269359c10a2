//! depth_edge_erosion: voids every depth-edge pixel, plus a 7×7 square around a `rate` fraction
//! of them (docs/src/perturbations.md §4), like the missing depth a real sensor shows along occlusion
//! boundaries.
//!
//! Edges: Canny on the depth normalised to 8 bits as ⌊255·z / max z⌋ (invalid = 0, so the rims
//! of holes are edges too): Sobel 3×3 with replicated borders, L1 magnitude, OpenCV's
//! non-maximum suppression, thresholds [`LOW`]/[`HIGH`], hysteresis. On the GPU the hysteresis
//! is up to [`HYSTERESIS_PASSES`] passes of a flood fill inside 16×16 tiles, so a weak chain
//! joins an edge if it reaches one within that many tile crossings (at least 16·N pixels); passes
//! after one that changed nothing are skipped by indirect dispatch. The twin mirrors exactly that.

use rslam_core::DepthImage;
use rslam_gpu::FrameTextures;

use crate::image::color_pass::KeyedParams;
use crate::perturbation::{view, Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::twin::{Tolerance, Twin};
use crate::{rng, PerturbError};

const NAME: &str = "depth_edge_erosion";
const SHADER: &str = "perturb/depth/depth_edge_erosion.wgsl";
const PURPOSE_CHOICE: u32 = 0;

/// Fraction of edge pixels that also void a 7×7 square (docs/src/perturbations.md §4).
pub const RATE: [f32; 5] = [0.015, 0.020, 0.025, 0.030, 0.035];
/// Canny thresholds on the L1 Sobel magnitude of the 8-bit depth (our choice, OpenCV's usual
/// 1:2 ratio): a step of 0.25·max z / 20 ≈ 1.25% of the range is weak, twice that strong.
pub const LOW: f32 = 50.0;
pub const HIGH: f32 = 100.0;
/// Global hysteresis passes (even, so the result ends in the texture it started from).
pub const HYSTERESIS_PASSES: usize = 8;
/// Half the side of the voided square.
const SQUARE_RADIUS: i64 = 3;
const TILE: usize = 16;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Depth,
    description: "voids depth edges (Canny on 8-bit 255z/max z: L1 Sobel, thresholds 50/100) plus a 7x7 square around a `rate` fraction of them",
    parameters: |s| format!("rate={}", RATE[s as usize - 1]),
    build: |kit| Ok(Box::new(EdgeErosion::new(kit)?)),
    between: Between::Interpolated("erosion rate linear from 0"),
    explicit: None,
    twin: Twin::Depth(twin),
    // Integer Canny on the 8-bit depth: the same pixels voided, the others untouched.
    twin_tolerance: Tolerance::EXACT,
    uniforms: &[KeyedParams::layout(SHADER)],
};

struct EdgeErosion {
    depth_max: wgpu::ComputePipeline,
    gradient: wgpu::ComputePipeline,
    suppress: wgpu::ComputePipeline,
    hysteresis: wgpu::ComputePipeline,
    plan_hysteresis: wgpu::ComputePipeline,
    choose: wgpu::ComputePipeline,
    void_rows: wgpu::ComputePipeline,
    void_columns: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    max_bits: wgpu::Buffer,
    changed: wgpu::Buffer,
    /// Indirect dispatch size of the next hysteresis pass, written by `plan_hysteresis`.
    next_pass: wgpu::Buffer,
}

impl EdgeErosion {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        let entry = |name| kit.pipeline_entry(SHADER, name);
        Ok(Self {
            depth_max: entry("depth_max")?,
            gradient: entry("gradient")?,
            suppress: entry("suppress")?,
            hysteresis: entry("hysteresis")?,
            plan_hysteresis: entry("plan_hysteresis")?,
            choose: entry("choose")?,
            void_rows: entry("void_rows")?,
            void_columns: entry("void_columns")?,
            params: kit.uniform_buffer::<KeyedParams>(SHADER),
            max_bits: kit.storage_buffer(SHADER, 4),
            changed: kit.storage_buffer(SHADER, 4),
            next_pass: kit.ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("depth_edge_erosion next pass"),
                size: 12,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::INDIRECT,
                mapped_at_creation: false,
            }),
        })
    }
}

impl GpuPerturbation for EdgeErosion {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        use wgpu::BindingResource as R;
        kit.write_uniform(
            &self.params,
            &KeyedParams {
                key: key.rng(NAME, PURPOSE_CHOICE).0,
                values: [key.interpolate(0.0, &RATE) as f32, LOW, HIGH, 0.0],
            },
        );
        encoder.clear_buffer(&self.max_bits, 0, None);
        encoder.clear_buffer(&self.changed, 0, None);
        let depth = frame.depth_view();
        let states = [view(&kit.scratch.float1[0]), view(&kit.scratch.float1[1])];
        let params = || self.params.as_entire_binding();
        let max_bits = || self.max_bits.as_entire_binding();
        let changed = || self.changed.as_entire_binding();

        let group = kit.bind_group_at(
            &self.depth_max,
            NAME,
            &[(0, R::TextureView(depth)), (2, max_bits())],
        );
        let columns = [kit.width.div_ceil(64), 1, 1];
        kit.dispatch_workgroups(encoder, &self.depth_max, &group, "depth_max", columns);
        let group = kit.bind_group_at(
            &self.gradient,
            NAME,
            &[
                (0, R::TextureView(depth)),
                (2, max_bits()),
                (4, R::TextureView(&states[0])),
            ],
        );
        kit.dispatch(encoder, &self.gradient, &group, "gradient");
        let group = kit.bind_group_at(
            &self.suppress,
            NAME,
            &[
                (1, params()),
                (3, R::TextureView(&states[0])),
                (4, R::TextureView(&states[1])),
                (5, changed()),
            ],
        );
        kit.dispatch(encoder, &self.suppress, &group, "suppress");
        // Up to HYSTERESIS_PASSES (even) passes ping-pong from states[1] and end in states[1].
        for pass in 0..HYSTERESIS_PASSES {
            let (from, to) = (&states[1 - pass % 2], &states[pass % 2]);
            let plan = kit.bind_group_at(
                &self.plan_hysteresis,
                NAME,
                &[
                    (3, R::TextureView(from)),
                    (5, changed()),
                    (6, self.next_pass.as_entire_binding()),
                ],
            );
            kit.dispatch_workgroups(
                encoder,
                &self.plan_hysteresis,
                &plan,
                "plan_hysteresis",
                [1, 1, 1],
            );
            let group = kit.bind_group_at(
                &self.hysteresis,
                NAME,
                &[
                    (3, R::TextureView(from)),
                    (4, R::TextureView(to)),
                    (5, changed()),
                ],
            );
            let mut compute = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("hysteresis"),
                timestamp_writes: None,
            });
            compute.set_pipeline(&self.hysteresis);
            compute.set_bind_group(0, &group, &[]);
            compute.dispatch_workgroups_indirect(&self.next_pass, 0);
        }
        let group = kit.bind_group_at(
            &self.choose,
            NAME,
            &[
                (1, params()),
                (3, R::TextureView(&states[1])),
                (4, R::TextureView(&states[0])),
            ],
        );
        kit.dispatch(encoder, &self.choose, &group, "choose");
        let group = kit.bind_group_at(
            &self.void_rows,
            NAME,
            &[
                (3, R::TextureView(&states[0])),
                (4, R::TextureView(&states[1])),
            ],
        );
        kit.dispatch(encoder, &self.void_rows, &group, "void_rows");
        let group = kit.bind_group_at(
            &self.void_columns,
            NAME,
            &[(0, R::TextureView(depth)), (3, R::TextureView(&states[1]))],
        );
        kit.dispatch(encoder, &self.void_columns, &group, "void_columns");
        Ok(())
    }
}

/// Canny edge states of a depth frame, as the GPU computes them: 0 none, 2 edge.
pub fn edges(depth: &DepthImage) -> Vec<u8> {
    let (w, h) = (depth.width as i64, depth.height as i64);
    let z_max = depth.data.iter().fold(0.0f32, |m, &z| m.max(z));
    let scale = if z_max > 0.0 { 255.0 / z_max } else { 0.0 };
    let d8: Vec<i32> = depth
        .data
        .iter()
        .map(|&z| (z.max(0.0) * scale).floor() as i32)
        .collect();
    let at = |x: i64, y: i64| d8[(y.clamp(0, h - 1) * w + x.clamp(0, w - 1)) as usize];
    let mut magnitude = vec![0i32; d8.len()];
    let mut direction = vec![0u8; d8.len()];
    for y in 0..h {
        for x in 0..w {
            let dx = (at(x + 1, y - 1) + 2 * at(x + 1, y) + at(x + 1, y + 1))
                - (at(x - 1, y - 1) + 2 * at(x - 1, y) + at(x - 1, y + 1));
            let dy = (at(x - 1, y + 1) + 2 * at(x, y + 1) + at(x + 1, y + 1))
                - (at(x - 1, y - 1) + 2 * at(x, y - 1) + at(x + 1, y - 1));
            let (xs, ys) = (dx.abs(), dy.abs());
            let tg22x = xs * 13573;
            let yq = ys << 15;
            let i = (y * w + x) as usize;
            magnitude[i] = xs + ys;
            direction[i] = if yq < tg22x {
                0
            } else if yq > tg22x + (xs << 16) {
                1
            } else if (dx ^ dy) < 0 {
                3
            } else {
                2
            };
        }
    }
    let mag = |x: i64, y: i64| {
        if x < 0 || y < 0 || x >= w || y >= h {
            0
        } else {
            magnitude[(y * w + x) as usize]
        }
    };
    let mut state = vec![0u8; d8.len()];
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let m = magnitude[i];
            if m as f32 <= LOW {
                continue;
            }
            let keep = match direction[i] {
                0 => m > mag(x - 1, y) && m >= mag(x + 1, y),
                1 => m > mag(x, y - 1) && m >= mag(x, y + 1),
                2 => m > mag(x - 1, y - 1) && m > mag(x + 1, y + 1),
                _ => m > mag(x + 1, y - 1) && m > mag(x - 1, y + 1),
            };
            if keep {
                state[i] = if m as f32 > HIGH { 2 } else { 1 };
            }
        }
    }
    for _ in 0..HYSTERESIS_PASSES {
        state = hysteresis_pass(&state, w as usize, h as usize);
    }
    state.iter().map(|&s| if s == 2 { 2 } else { 0 }).collect()
}

/// One global hysteresis pass: inside each tile, flood "edge" (2) into weak (1) pixels,
/// seeded by edges in the tile and its one-pixel halo, reading the halo from `state`.
fn hysteresis_pass(state: &[u8], w: usize, h: usize) -> Vec<u8> {
    let mut out = state.to_vec();
    for ty in (0..h).step_by(TILE) {
        for tx in (0..w).step_by(TILE) {
            let inside = |x: usize, y: usize| {
                x >= tx && x < (tx + TILE).min(w) && y >= ty && y < (ty + TILE).min(h)
            };
            let mut stack: Vec<(usize, usize)> = Vec::new();
            for y in ty.saturating_sub(1)..(ty + TILE + 1).min(h) {
                for x in tx.saturating_sub(1)..(tx + TILE + 1).min(w) {
                    if state[y * w + x] == 2 {
                        stack.push((x, y));
                    }
                }
            }
            while let Some((x, y)) = stack.pop() {
                for ny in y.saturating_sub(1)..=(y + 1).min(h - 1) {
                    for nx in x.saturating_sub(1)..=(x + 1).min(w - 1) {
                        let j = ny * w + nx;
                        if inside(nx, ny) && out[j] == 1 {
                            out[j] = 2;
                            stack.push((nx, ny));
                        }
                    }
                }
            }
        }
    }
    out
}

/// Edge pixels chosen for a 7×7 square on this frame.
pub fn chosen(edges: &[u8], width: u32, key: &FrameKey) -> Vec<bool> {
    let rng = key.rng(NAME, PURPOSE_CHOICE);
    let rate = key.interpolate(0.0, &RATE) as f32;
    edges
        .iter()
        .enumerate()
        .map(|(i, &e)| {
            let (x, y) = (i as u32 % width, i as u32 / width);
            e == 2 && rng::uniform(rng.draw([x, y, 0, 0])[0]) < rate
        })
        .collect()
}

/// CPU twin of `depth_edge_erosion.wgsl`.
pub fn twin(depth: &DepthImage, key: &FrameKey) -> DepthImage {
    let (w, h) = (depth.width as i64, depth.height as i64);
    let edges = edges(depth);
    let chosen = chosen(&edges, depth.width, key);
    let mut out = depth.clone();
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let near_chosen = (-SQUARE_RADIUS..=SQUARE_RADIUS).any(|dy| {
                (-SQUARE_RADIUS..=SQUARE_RADIUS).any(|dx| {
                    let (nx, ny) = (x + dx, y + dy);
                    nx >= 0 && ny >= 0 && nx < w && ny < h && chosen[(ny * w + nx) as usize]
                })
            });
            if edges[i] == 2 || near_chosen {
                out.data[i] = 0.0;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    /// A box at 1.8 m before a 4 m wall: edges lie on its outline, one pixel thick, and not on
    /// the flat wall or box face; invalid pixels stay invalid.
    #[test]
    fn edges_follow_depth_discontinuities() {
        let (w, h) = (120u32, 90u32);
        let mut depth = DepthImage::new(w, h);
        for y in 0..h {
            for x in 0..w {
                let in_box = (40..80).contains(&x) && (30..60).contains(&y);
                depth.data[(y * w + x) as usize] = if in_box { 1.8 } else { 4.0 };
            }
        }
        let e = edges(&depth);
        let edge_at = |x: u32, y: u32| e[(y * w + x) as usize] == 2;
        for y in 0..h {
            for x in 0..w {
                let near_outline = (38..=81).contains(&x)
                    && (28..=61).contains(&y)
                    && !((42..78).contains(&x) && (32..58).contains(&y));
                if edge_at(x, y) {
                    assert!(near_outline, "edge at ({x}, {y}) away from the box outline");
                }
            }
        }
        // Every row of the box's left side has an edge in one of its two boundary columns.
        for y in 32..58 {
            assert!(
                edge_at(39, y) ^ edge_at(40, y),
                "row {y}: one edge pixel across the step"
            );
        }
        let out = testing::run_depth(&ENTRY, &testing::key(0, 5), &depth);
        let voided = out.data.iter().filter(|&&z| z == 0.0).count();
        assert!(
            voided > 0 && voided < (w * h / 4) as usize,
            "voided {voided}"
        );
    }

    /// Hysteresis: a weak step (magnitude 60) continuing a strong one (204) is an edge along its
    /// whole length, across several tiles; a weak step without a strong part is not.
    #[test]
    fn weak_edges_join_only_when_connected_to_strong_ones() {
        let (w, h) = (160u32, 100u32);
        let mut depth = DepthImage::new(w, h);
        for y in 0..h {
            for x in 0..w {
                // max z = 10 → 8-bit depth ⌊25.5 z⌋: 5 m → 127, 5.6 m → 142, 7 m → 178.
                let z = match x {
                    0..60 => 5.0,
                    60..100 if y < 6 => 7.0,
                    60..100 => 5.6,
                    100..130 => 5.0,
                    _ => 5.6,
                };
                depth.data[(y * w + x) as usize] = z;
            }
        }
        depth.data[0] = 10.0;
        let e = edges(&depth);
        let row_edges =
            |y: u32, xs: std::ops::Range<u32>| xs.filter(|&x| e[(y * w + x) as usize] == 2).count();
        for y in 1..h {
            assert!(row_edges(y, 57..62) >= 1, "connected weak step, row {y}");
            assert_eq!(row_edges(y, 120..140), 0, "isolated weak step, row {y}");
        }
        let key = testing::key(2, 1);
        let gpu = testing::run_depth(&ENTRY, &key, &depth);
        testing::assert_depth_close(&gpu, &twin(&depth, &key), 0.0, "erosion-hysteresis");
    }

    #[test]
    fn chosen_fraction_is_the_rate_and_invalid_stays_invalid() {
        let depth = testing::test_depth(640, 480);
        let e = edges(&depth);
        let edge_count = e.iter().filter(|&&s| s == 2).count() as f64;
        assert!(edge_count > 1000.0, "{edge_count} edge pixels");
        for severity in [1u8, 5] {
            let mut picked = 0usize;
            let frames = 20;
            for frame in 0..frames {
                let key = FrameKey {
                    frame,
                    ..testing::key(3, severity)
                };
                picked += chosen(&e, depth.width, &key).iter().filter(|&&c| c).count();
            }
            let rate = RATE[severity as usize - 1] as f64;
            let n = edge_count * frames as f64;
            let got = picked as f64 / n;
            assert!(
                (got - rate).abs() < 5.0 * (rate * (1.0 - rate) / n).sqrt(),
                "severity {severity}: {got}"
            );
        }
        let out = twin(&depth, &testing::key(3, 5));
        for (o, d) in out.data.iter().zip(&depth.data) {
            assert!(*d != 0.0 || *o == 0.0);
        }
    }

    #[test]
    fn seeded() {
        testing::assert_seeded(&ENTRY, 3);
    }
}
