//! depth_missing: voids `count` rectangles of ⌊0.1H⌋×⌊0.1W⌋ pixels whose top-left corners are
//! uniform over the positions that keep the rectangle inside the frame (docs/src/perturbations.md §4).
//! Rectangles may overlap. Positions are drawn on the CPU from the frame's key.

use bytemuck::{Pod, Zeroable};
use rslam_core::DepthImage;
use rslam_gpu::FrameTextures;

use crate::perturbation::{
    Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit, WORKGROUP,
};
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, UniformLayout};
use crate::PerturbError;

const NAME: &str = "depth_missing";
const SHADER: &str = "perturb/depth/depth_missing.wgsl";
const PURPOSE_RECTANGLES: u32 = 0;

/// Rectangles per severity (docs/src/perturbations.md §4, the Robust-SLAM benchmark).
pub const COUNT: [u32; 5] = [2, 4, 6, 8, 10];
const MAX_COUNT: usize = 10;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Depth,
    description: "voids N rectangles of 0.1H x 0.1W at uniform random positions per frame",
    parameters: |s| format!("{} rectangles", COUNT[s as usize - 1]),
    build: |kit| {
        Ok(Box::new(DepthMissing {
            pipeline: kit.pipeline(SHADER)?,
            params: kit.uniform_buffer::<Params>(SHADER),
        }))
    },
    between: Between::Interpolated("rectangle count linear from 0, rounded"),
    explicit: None,
    twin: Twin::Depth(twin),
    // The rectangles are drawn on the CPU; the shader only voids them.
    twin_tolerance: Tolerance::EXACT,
    uniforms: &[UniformLayout {
        rust: rust_layout!(Params { count, rects }),
        wgsl: "Params",
        shader: SHADER,
    }],
};

/// Rectangles at the frame's severity: linear in the count from 0, rounded to a whole one.
fn count(key: &FrameKey) -> u32 {
    key.interpolate(0.0, &COUNT).round() as u32
}

/// A half-open pixel rectangle [x0, x1) × [y0, y1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rect {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

/// The rectangles of one frame.
pub fn rectangles(width: u32, height: u32, key: &FrameKey) -> Vec<Rect> {
    let (w, h) = (width / 10, height / 10);
    let rng = key.rng(NAME, PURPOSE_RECTANGLES);
    (0..count(key))
        .map(|i| {
            let x0 = (rng.uniform_f64([i, 0, 0, 0]) * (width - w + 1) as f64) as u32;
            let y0 = (rng.uniform_f64([i, 1, 0, 0]) * (height - h + 1) as f64) as u32;
            Rect {
                x0,
                y0,
                x1: x0 + w,
                y1: y0 + h,
            }
        })
        .collect()
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Params {
    count: [u32; 4],
    rects: [[u32; 4]; MAX_COUNT],
}

struct DepthMissing {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
}

impl GpuPerturbation for DepthMissing {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        let rects = rectangles(kit.width, kit.height, key);
        let mut params = Params {
            count: [rects.len() as u32, 0, 0, 0],
            rects: [[0; 4]; MAX_COUNT],
        };
        for (slot, r) in params.rects.iter_mut().zip(&rects) {
            *slot = [r.x0, r.y0, r.x1, r.y1];
        }
        kit.write_uniform(&self.params, &params);
        let depth = frame.depth_view();
        let group = kit.bind_group(
            &self.pipeline,
            NAME,
            &[
                wgpu::BindingResource::TextureView(depth),
                self.params.as_entire_binding(),
            ],
        );
        let (w, h) = (kit.width / 10, kit.height / 10);
        let groups = [
            w.div_ceil(WORKGROUP),
            h.div_ceil(WORKGROUP),
            rects.len() as u32,
        ];
        if !rects.is_empty() && w > 0 && h > 0 {
            kit.dispatch_workgroups(encoder, &self.pipeline, &group, NAME, groups);
        }
        Ok(())
    }
}

/// CPU twin of `depth_missing.wgsl`.
pub fn twin(depth: &DepthImage, key: &FrameKey) -> DepthImage {
    let mut out = depth.clone();
    for r in rectangles(depth.width, depth.height, key) {
        for y in r.y0..r.y1 {
            for x in r.x0..r.x1 {
                out.data[(y * depth.width + x) as usize] = 0.0;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn rectangles_have_the_size_and_stay_inside() {
        for frame in 0..50 {
            let key = FrameKey {
                frame,
                ..testing::key(1, 5)
            };
            let rects = rectangles(1200, 680, &key);
            assert_eq!(rects.len(), 10);
            for r in rects {
                assert_eq!((r.x1 - r.x0, r.y1 - r.y0), (120, 68));
                assert!(r.x1 <= 1200 && r.y1 <= 680);
            }
        }
    }

    /// Voided fraction against the expectation for independent uniform rectangles: a pixel is
    /// missed by one rectangle with probability 1 − p(x)p(y), p = coverage of its row/column.
    #[test]
    fn missing_fraction_matches_expectation() {
        let (w, h) = (200u32, 100u32);
        let full = DepthImage {
            width: w,
            height: h,
            data: vec![2.0; (w * h) as usize],
        };
        let cover = |n: u32, size: u32, i: u32| {
            let positions = n - size + 1;
            let first = i.saturating_sub(size - 1);
            let last = i.min(n - size);
            (last - first + 1) as f64 / positions as f64
        };
        for severity in [1u8, 5] {
            let count = COUNT[severity as usize - 1] as i32;
            let mut expected = 0.0;
            for y in 0..h {
                for x in 0..w {
                    let p = cover(w, w / 10, x) * cover(h, h / 10, y);
                    expected += 1.0 - (1.0 - p).powi(count);
                }
            }
            expected /= (w * h) as f64;
            let frames = 200;
            let mut missing = 0usize;
            for frame in 0..frames {
                let key = FrameKey {
                    frame,
                    ..testing::key(2, severity)
                };
                missing += twin(&full, &key).data.iter().filter(|&&z| z == 0.0).count();
            }
            let got = missing as f64 / (frames * w * h) as f64;
            assert!(
                (got - expected).abs() < 0.01,
                "severity {severity}: {got} vs {expected}"
            );
        }
    }

    #[test]
    fn seeded() {
        testing::assert_seeded(&ENTRY, 3);
    }
}
