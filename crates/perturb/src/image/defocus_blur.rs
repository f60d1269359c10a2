//! defocus_blur: imagecorruptions' `defocus_blur`, OpenCV `filter2D` (BORDER_REFLECT_101) with
//! their `disk` kernel: a normalised disk, smoothed by a small Gaussian of the anti-alias σ.
//! Applied exactly as a sum of centred row boxes over running row sums (two passes), which reads
//! ~2 texels per box instead of one per kernel tap.

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use super::kernels::{store_truncated, Edge};
use super::textures::storage_texture;
use crate::image_f32::RgbF32;
use crate::perturbation::{view, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, UniformLayout};
use crate::PerturbError;

const NAME: &str = "defocus_blur";
const ROWS_SHADER: &str = "perturb/image/defocus_blur_rows.wgsl";
const BOXES_SHADER: &str = "perturb/image/defocus_blur.wgsl";

/// (disk radius px, anti-alias σ) per severity (perturbations.md §3, imagecorruptions).
pub const RADIUS_ALIAS: [(u32, f64); 5] = [(3, 0.1), (4, 0.5), (6, 0.5), (8, 0.5), (10, 0.5)];

/// Boxes whose whole contribution |a|·(2k+1) is below this are dropped (at most 4e-6 of the
/// kernel's mass in all, far below one 8-bit level).
const NEGLIGIBLE_BOX: f64 = 1e-6;

const MAX_BOXES: usize = 128;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "defocus blur: anti-aliased disk kernel (OpenCV filter2D, reflect-101 edges)",
    parameters: |s| {
        let (radius, alias) = RADIUS_ALIAS[s as usize - 1];
        format!("disk radius={radius}px anti-alias σ={alias}")
    },
    build: |kit| Ok(Box::new(DefocusBlur::new(kit)?)),
    explicit: None,
    twin: Twin::Color(twin),
    // f32 running sums: the same order on both sides, but fused multiply-adds on the GPU.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[
        UniformLayout {
            rust: rust_layout!(PrefixParams { radius }),
            wgsl: "Prefix",
            shader: ROWS_SHADER,
        },
        UniformLayout {
            rust: rust_layout!(BoxParams {
                radius,
                count,
                offset,
                boxes
            }),
            wgsl: "Boxes",
            shader: BOXES_SHADER,
        },
    ],
};

/// A square kernel of side 2·radius+1, row-major.
#[derive(Clone, Debug)]
pub struct SquareKernel {
    pub radius: usize,
    pub weights: Vec<f64>,
}

/// imagecorruptions' `disk(radius, alias_blur)`: a 17×17 window (radius ≤ 8, 3×3 Gaussian) or a
/// (2r+1)² window (5×5 Gaussian), the disk x²+y² ≤ r² normalised, then `cv2.GaussianBlur` with
/// BORDER_REFLECT_101 inside the window (which is why severities 4–5 sum to slightly over 1).
pub fn disk_kernel(radius: u32, alias_sigma: f64) -> SquareKernel {
    let (half, ksize) = if radius <= 8 {
        (8usize, 3usize)
    } else {
        (radius as usize, 5)
    };
    let side = 2 * half + 1;
    let r2 = (radius * radius) as i64;
    let mut disk: Vec<f64> = (0..side * side)
        .map(|i| {
            let (x, y) = (
                (i % side) as i64 - half as i64,
                (i / side) as i64 - half as i64,
            );
            if x * x + y * y <= r2 {
                1.0
            } else {
                0.0
            }
        })
        .collect();
    let total: f64 = disk.iter().sum();
    disk.iter_mut().for_each(|v| *v /= total);
    // cv2.getGaussianKernel(ksize, σ): exp(−(i − (k−1)/2)²/2σ²), normalised.
    let centre = (ksize as f64 - 1.0) / 2.0;
    let raw: Vec<f64> = (0..ksize)
        .map(|i| (-(i as f64 - centre).powi(2) / (2.0 * alias_sigma * alias_sigma)).exp())
        .collect();
    let sum: f64 = raw.iter().sum();
    let gauss: Vec<f64> = raw.iter().map(|g| g / sum).collect();
    let g_half = (ksize / 2) as i64;
    let n = side as i64;
    let blur = |plane: &[f64], horizontal: bool| -> Vec<f64> {
        (0..side * side)
            .map(|i| {
                let (x, y) = ((i % side) as i64, (i / side) as i64);
                (0..ksize as i64)
                    .map(|t| {
                        let o = t - g_half;
                        let (sx, sy) = if horizontal {
                            (Edge::Reflect101.index(x + o, n) as i64, y)
                        } else {
                            (x, Edge::Reflect101.index(y + o, n) as i64)
                        };
                        gauss[t as usize] * plane[(sy * n + sx) as usize]
                    })
                    .sum()
            })
            .collect()
    };
    let weights = blur(&blur(&disk, true), false);
    SquareKernel {
        radius: half,
        weights,
    }
}

/// One centred row box of a kernel: weight `a` on columns −k..=k of row `dy`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RowBox {
    pub dy: i32,
    pub k: i32,
    pub a: f32,
}

/// Each (symmetric) kernel row p(|x|) written as Σ_k (p(k) − p(k+1))·box(k).
pub fn row_boxes(kernel: &SquareKernel) -> Vec<RowBox> {
    let r = kernel.radius;
    let side = 2 * r + 1;
    let mut boxes = Vec::new();
    for row in 0..side {
        // The two halves agree to ~1e-10; average them so the decomposition is symmetric.
        let p = |k: usize| -> f64 {
            if k > r {
                return 0.0;
            }
            let w = &kernel.weights[row * side..(row + 1) * side];
            0.5 * (w[r + k] + w[r - k])
        };
        for k in 0..=r {
            let a = p(k) - p(k + 1);
            if a.abs() * (2 * k + 1) as f64 >= NEGLIGIBLE_BOX {
                boxes.push(RowBox {
                    dy: row as i32 - r as i32,
                    k: k as i32,
                    a: a as f32,
                });
            }
        }
    }
    boxes
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct PrefixParams {
    radius: i32,
    _pad: [i32; 3],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct BoxParams {
    radius: i32,
    count: i32,
    offset: f32,
    _pad: f32,
    boxes: [[f32; 4]; MAX_BOXES],
}

fn box_params(severity: u8) -> Result<BoxParams, PerturbError> {
    let (radius, alias) = RADIUS_ALIAS[severity as usize - 1];
    let kernel = disk_kernel(radius, alias);
    let boxes = row_boxes(&kernel);
    if boxes.len() > MAX_BOXES {
        return Err(PerturbError::Unsupported {
            name: NAME.into(),
            message: format!(
                "{} kernel boxes exceed the shader's {MAX_BOXES}",
                boxes.len()
            ),
        });
    }
    let mut packed = [[0.0; 4]; MAX_BOXES];
    for (slot, b) in packed.iter_mut().zip(&boxes) {
        *slot = [b.dy as f32, b.k as f32, b.a, 0.0];
    }
    let mass: f32 = boxes.iter().map(|b| b.a * (2 * b.k + 1) as f32).sum();
    Ok(BoxParams {
        radius: kernel.radius as i32,
        count: boxes.len() as i32,
        offset: 0.5 * mass,
        _pad: 0.0,
        boxes: packed,
    })
}

struct DefocusBlur {
    rows: wgpu::ComputePipeline,
    boxes: wgpu::ComputePipeline,
    prefix_params: wgpu::Buffer,
    box_params: wgpu::Buffer,
    prefix: wgpu::Texture,
}

impl DefocusBlur {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        let widest = RADIUS_ALIAS
            .iter()
            .map(|&(r, _)| r.max(8))
            .max()
            .unwrap_or(8);
        Ok(Self {
            rows: kit.pipeline(ROWS_SHADER)?,
            boxes: kit.pipeline(BOXES_SHADER)?,
            prefix_params: kit.uniform_buffer::<PrefixParams>("defocus prefix"),
            box_params: kit.uniform_buffer::<BoxParams>("defocus boxes"),
            prefix: storage_texture(
                kit,
                "defocus running sums",
                wgpu::TextureFormat::Rgba32Float,
                kit.width + 2 * widest + 1 + 8,
                kit.height,
            ),
        })
    }
}

impl GpuPerturbation for DefocusBlur {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        let params = box_params(key.severity)?;
        let prefix_params = PrefixParams {
            radius: params.radius,
            _pad: [0; 3],
        };
        kit.write_uniform(&self.prefix_params, &prefix_params);
        kit.write_uniform(&self.box_params, &params);
        let prefix = view(&self.prefix);
        let color = frame.color_view();
        let rows = kit.bind_group(
            &self.rows,
            "defocus rows",
            &[
                wgpu::BindingResource::TextureView(color),
                wgpu::BindingResource::TextureView(&prefix),
                self.prefix_params.as_entire_binding(),
            ],
        );
        let groups = [kit.height.div_ceil(64), 1, 1];
        kit.dispatch_workgroups(encoder, &self.rows, &rows, "defocus rows", groups);
        let boxes = kit.bind_group(
            &self.boxes,
            "defocus boxes",
            &[
                wgpu::BindingResource::TextureView(&prefix),
                wgpu::BindingResource::TextureView(color),
                self.box_params.as_entire_binding(),
            ],
        );
        let runs = kit.width.div_ceil(8);
        kit.dispatch_grid(
            encoder,
            &self.boxes,
            &boxes,
            "defocus boxes",
            runs,
            kit.height,
        );
        Ok(())
    }
}

/// CPU twin of the two passes: the same running sums (same order) and box differences.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let params = box_params(key.severity).expect("the severity tables fit the shader");
    let (w, h) = (image.width as i64, image.height as i64);
    let r = params.radius as i64;
    let extended = (w + 2 * r + 1) as usize;
    let mut prefix = vec![[0.0f32; 3]; extended * h as usize];
    for y in 0..h {
        let row = &mut prefix[y as usize * extended..(y as usize + 1) * extended];
        let mut sum = [0.0f32; 3];
        for j in 0..(w + 2 * r) {
            let x = Edge::Reflect101.index(j - r, w) as u32;
            let v = image.at(x, y as u32);
            sum = std::array::from_fn(|c| sum[c] + (v[c] - 0.5));
            row[j as usize + 1] = sum;
        }
    }
    let mut out = image.clone();
    for y in 0..h {
        for x in 0..w {
            let mut sum = [params.offset; 3];
            for b in &params.boxes[..params.count as usize] {
                let (dy, k, a) = (b[0] as i64, b[1] as i64, b[2]);
                let row = Edge::Reflect101.index(y + dy, h) * extended;
                let right = prefix[row + (x + k + r + 1) as usize];
                let left = prefix[row + (x - k + r) as usize];
                sum = std::array::from_fn(|c| sum[c] + a * (right[c] - left[c]));
            }
            let i = out.index(x as u32, y as u32);
            out.data[i] = sum.map(store_truncated);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn kernel_matches_imagecorruptions_disk() {
        // Values from imagecorruptions' disk() (cv2 4.x / 5.x): sums and the centre weight.
        let k3 = disk_kernel(3, 0.1);
        assert_eq!(k3.radius, 8);
        let sum: f64 = k3.weights.iter().sum();
        assert!((sum - 1.0).abs() < 1e-6);
        assert!(
            (k3.weights[8 * 17 + 8] - 1.0 / 29.0).abs() < 1e-6,
            "29 pixels in r=3"
        );
        let sum8: f64 = disk_kernel(8, 0.5).weights.iter().sum();
        assert!((sum8 - 1.012_975_45).abs() < 1e-6, "{sum8}");
        let k10 = disk_kernel(10, 0.5);
        assert_eq!(k10.radius, 10);
        let sum10: f64 = k10.weights.iter().sum();
        assert!((sum10 - 1.010_785_8).abs() < 1e-6, "{sum10}");
    }

    #[test]
    fn boxes_rebuild_the_kernel() {
        for &(radius, alias) in &RADIUS_ALIAS {
            let kernel = disk_kernel(radius, alias);
            let side = 2 * kernel.radius + 1;
            let mut rebuilt = vec![0.0f64; side * side];
            for b in row_boxes(&kernel) {
                let row = (b.dy + kernel.radius as i32) as usize;
                for x in -b.k..=b.k {
                    rebuilt[row * side + (x + kernel.radius as i32) as usize] += b.a as f64;
                }
            }
            let worst = rebuilt
                .iter()
                .zip(&kernel.weights)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(worst < 2e-6, "radius {radius}: {worst}");
        }
    }

    #[test]
    fn twin_equals_direct_filtering_with_the_kernel() {
        // The box/running-sum route equals filter2D with the dense kernel (reflect-101 edges).
        let clean = RgbF32::from_rgb8(&testing::test_image(40, 32));
        for severity in [1, 5] {
            let (radius, alias) = RADIUS_ALIAS[severity as usize - 1];
            let kernel = disk_kernel(radius, alias);
            let r = kernel.radius as i64;
            let side = 2 * r + 1;
            let out = twin(&clean, &testing::key(0, severity));
            for (x, y) in [(0u32, 0u32), (5, 7), (20, 16), (39, 31)] {
                let mut direct = [0.0f64; 3];
                for dy in -r..=r {
                    for dx in -r..=r {
                        let w = kernel.weights[((dy + r) * side + dx + r) as usize];
                        let sx = Edge::Reflect101.index(x as i64 + dx, 40) as u32;
                        let sy = Edge::Reflect101.index(y as i64 + dy, 32) as u32;
                        let v = clean.at(sx, sy);
                        (0..3).for_each(|c| direct[c] += w * v[c] as f64);
                    }
                }
                let got = out.at(x, y);
                for c in 0..3 {
                    let expected = (direct[c].clamp(0.0, 1.0) * 255.0).floor() / 255.0;
                    assert!(
                        (got[c] as f64 - expected).abs() <= 1.0 / 255.0 + 1e-6,
                        "severity {severity} ({x},{y}) c{c}: {} vs {expected}",
                        got[c]
                    );
                }
            }
        }
    }
}
