//! defocus_blur: imagecorruptions' `defocus_blur`, OpenCV `filter2D` (BORDER_REFLECT_101) with
//! their `disk` kernel: a normalised disk, smoothed by a small Gaussian of the anti-alias σ.
//! Applied exactly, split as kernel = Gaussian ⊛ disk + correction: the first pass blurs each row
//! with the small Gaussian on the fly and keeps running row sums of the blurred and of the plain
//! image; the second adds one centred row box per disk row over the blurred sums and the few
//! boxes of the correction (what the reference's blur inside a finite window adds at its edges;
//! none below severity 4) over the plain sums. Each box is ~2 texel reads, and the disk has one
//! box per row where the smoothed kernel has 4–6 (13 against 62 boxes at severity 3).

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use super::kernels::{store_truncated, Edge};
use super::textures::storage_texture;
use crate::image_f32::RgbF32;
use crate::perturbation::{view, Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::severity::Severity;
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, UniformLayout};
use crate::PerturbError;

const NAME: &str = "defocus_blur";
const ROWS_SHADER: &str = "perturb/image/defocus_blur_rows.wgsl";
const BOXES_SHADER: &str = "perturb/image/defocus_blur.wgsl";

/// (disk radius px, anti-alias σ) per severity (docs/src/perturbations.md §3, imagecorruptions).
pub const RADIUS_ALIAS: [(u32, f64); 5] = [(3, 0.1), (4, 0.5), (6, 0.5), (8, 0.5), (10, 0.5)];

/// Boxes whose whole contribution |a|·(2k+1) is below this are dropped (at most 4e-6 of the
/// kernel's mass in all, far below one 8-bit level).
const NEGLIGIBLE_BOX: f64 = 1e-6;

const MAX_BOXES: usize = 128;

/// Taps of the anti-alias Gaussian the shader applies (offsets −2..=2; 3-tap kernels padded
/// with zeros).
const GAUSS_TAPS: usize = 5;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "defocus blur: anti-aliased disk kernel (OpenCV filter2D, reflect-101 edges)",
    parameters: |s| {
        let (radius, alias) = RADIUS_ALIAS[s as usize - 1];
        format!("disk radius={radius}px anti-alias σ={alias}")
    },
    build: |kit| Ok(Box::new(DefocusBlur::new(kit)?)),
    between: Between::Interpolated("radius (rounded) and alias σ linear from 0"),
    explicit: None,
    twin: Twin::Color(twin),
    // f32 running sums: the same order on both sides, but fused multiply-adds on the GPU.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[
        UniformLayout {
            rust: rust_layout!(PrefixParams { radius, gauss }),
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
    let disk = normalised_disk(radius);
    let gauss = anti_alias_taps(radius, alias_sigma);
    let half = (gauss.len() / 2) as i64;
    let side = 2 * disk.radius + 1;
    let n = side as i64;
    let blur = |plane: &[f64], horizontal: bool| -> Vec<f64> {
        (0..side * side)
            .map(|i| {
                let (x, y) = ((i % side) as i64, (i / side) as i64);
                (0..gauss.len() as i64)
                    .map(|t| {
                        let o = t - half;
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
    SquareKernel {
        radius: disk.radius,
        weights: blur(&blur(&disk.weights, true), false),
    }
}

/// The disk x²+y² ≤ r², normalised, in imagecorruptions' window (radius 8, or r when larger).
fn normalised_disk(radius: u32) -> SquareKernel {
    let half = (radius as usize).max(8);
    let side = 2 * half + 1;
    let r2 = (radius * radius) as i64;
    let mut weights: Vec<f64> = (0..side * side)
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
    let total: f64 = weights.iter().sum();
    weights.iter_mut().for_each(|v| *v /= total);
    SquareKernel {
        radius: half,
        weights,
    }
}

/// `cv2.getGaussianKernel(ksize, σ)` with imagecorruptions' ksize (3 up to radius 8, else 5):
/// exp(−(i − (k−1)/2)²/2σ²), normalised.
fn anti_alias_taps(radius: u32, sigma: f64) -> Vec<f64> {
    let ksize = if radius <= 8 { 3 } else { 5 };
    let centre = (ksize as f64 - 1.0) / 2.0;
    let raw: Vec<f64> = (0..ksize)
        .map(|i| (-(i as f64 - centre).powi(2) / (2.0 * sigma * sigma)).exp())
        .collect();
    let sum: f64 = raw.iter().sum();
    raw.iter().map(|g| g / sum).collect()
}

/// The kernel as the shaders apply it: `disk` boxes over the image blurred by `gauss`
/// (offsets −2..=2), plus `correction` boxes over the plain image.
#[derive(Clone, Debug)]
pub struct SplitKernel {
    pub gauss: [f64; GAUSS_TAPS],
    pub disk: Vec<RowBox>,
    pub correction: Vec<RowBox>,
    /// Half side of the whole kernel, correction included.
    pub radius: usize,
}

/// Splits imagecorruptions' kernel K as K = G ⊛ D + C: G the anti-alias Gaussian, D the disk, C
/// what their blur inside the finite window adds (its reflected edges) or drops (what spills
/// past the window); C is zero to below [`NEGLIGIBLE_BOX`] unless the disk reaches the window's
/// edge (severities 4 and 5).
pub fn split_kernel(radius: u32, alias_sigma: f64) -> SplitKernel {
    let disk = normalised_disk(radius);
    let taps = anti_alias_taps(radius, alias_sigma);
    let half = taps.len() / 2;
    let mut gauss = [0.0; GAUSS_TAPS];
    gauss[GAUSS_TAPS / 2 - half..=GAUSS_TAPS / 2 + half].copy_from_slice(&taps);
    // G ⊛ D and K on the window widened by the Gaussian's reach; their difference is C.
    let wide = disk.radius + half;
    let side = 2 * wide + 1;
    let inner = 2 * disk.radius + 1;
    let at = |kernel: &[f64], x: i64, y: i64| -> f64 {
        let (x, y) = (x + disk.radius as i64, y + disk.radius as i64);
        if (0..inner as i64).contains(&x) && (0..inner as i64).contains(&y) {
            kernel[y as usize * inner + x as usize]
        } else {
            0.0
        }
    };
    let reference = disk_kernel(radius, alias_sigma);
    let correction: Vec<f64> = (0..side * side)
        .map(|i| {
            let (x, y) = (
                (i % side) as i64 - wide as i64,
                (i / side) as i64 - wide as i64,
            );
            let mut blurred = 0.0;
            for (ty, gy) in taps.iter().enumerate() {
                for (tx, gx) in taps.iter().enumerate() {
                    let (ox, oy) = (tx as i64 - half as i64, ty as i64 - half as i64);
                    blurred += gx * gy * at(&disk.weights, x - ox, y - oy);
                }
            }
            at(&reference.weights, x, y) - blurred
        })
        .collect();
    SplitKernel {
        gauss,
        disk: row_boxes(&disk),
        correction: row_boxes(&SquareKernel {
            radius: wide,
            weights: correction,
        }),
        radius: wide,
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
    gauss: [[f32; 4]; GAUSS_TAPS],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct BoxParams {
    radius: i32,
    count: i32,
    offset: f32,
    _pad: f32,
    /// (dy, k, a, first prefix row: 0 for the blurred image's running sums, the height for the
    /// plain image's)
    boxes: [[f32; 4]; MAX_BOXES],
}

struct Params {
    prefix: PrefixParams,
    boxes: BoxParams,
}

/// Uniforms for `severity` on an image `height` rows high: radius and alias σ linear between
/// the table's rows from (0, 0) at severity 0, the disk's radius rounded to whole pixels.
fn params(severity: Severity, height: u32) -> Result<Params, PerturbError> {
    let radius = severity
        .interpolate(0.0, &RADIUS_ALIAS.map(|(r, _)| r as f64))
        .round() as u32;
    let alias = severity.interpolate(0.0, &RADIUS_ALIAS.map(|(_, a)| a));
    let split = split_kernel(radius, alias);
    let plain_row = height as i32;
    let boxes: Vec<(RowBox, i32)> = (split.disk.iter().map(|&b| (b, 0)))
        .chain(split.correction.iter().map(|&b| (b, plain_row)))
        .collect();
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
    for (slot, (b, row)) in packed.iter_mut().zip(&boxes) {
        *slot = [b.dy as f32, b.k as f32, b.a, *row as f32];
    }
    let mass: f32 = boxes.iter().map(|(b, _)| b.a * (2 * b.k + 1) as f32).sum();
    Ok(Params {
        prefix: PrefixParams {
            radius: split.radius as i32,
            _pad: [0; 3],
            gauss: split.gauss.map(|g| [g as f32, 0.0, 0.0, 0.0]),
        },
        boxes: BoxParams {
            radius: split.radius as i32,
            count: boxes.len() as i32,
            offset: 0.5 * mass,
            _pad: 0.0,
            boxes: packed,
        },
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
            .map(|&(r, alias)| split_kernel(r, alias).radius as u32)
            .max()
            .unwrap_or(0);
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
                2 * kit.height,
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
        let params = params(key.severity, kit.height)?;
        kit.write_uniform(&self.prefix_params, &params.prefix);
        kit.write_uniform(&self.box_params, &params.boxes);
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

/// CPU twin of the two passes: the same blurred and plain running sums (same order) and box
/// differences.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let params = params(key.severity, image.height).expect("the severity tables fit the shader");
    let (w, h) = (image.width as i64, image.height as i64);
    let r = params.prefix.radius as i64;
    let gauss = params.prefix.gauss.map(|g| g[0]);
    let reach = (GAUSS_TAPS / 2) as i64;
    let extended = (w + 2 * r + 1) as usize;
    let centred = |x: i64, y: i64| image.at(x as u32, y as u32).map(|v| v - 0.5);
    // Rows 0..h: running sums of the Gaussian-blurred image; rows h..2h: of the plain image.
    let mut prefix = vec![[0.0f32; 3]; extended * 2 * h as usize];
    for y in 0..h {
        let column = |j: i64| -> [f32; 3] {
            let x = Edge::Reflect101.index(j - r, w) as i64;
            let mut sum = [0.0f32; 3];
            for (t, g) in gauss.iter().enumerate() {
                let v = centred(x, Edge::Reflect101.index(y + t as i64 - reach, h) as i64);
                sum = std::array::from_fn(|c| sum[c] + g * v[c]);
            }
            sum
        };
        let (mut blurred_sum, mut plain_sum) = ([0.0f32; 3], [0.0f32; 3]);
        for j in 0..(w + 2 * r) {
            let mut blurred = [0.0f32; 3];
            for (t, g) in gauss.iter().enumerate() {
                let v = column(j + t as i64 - reach);
                blurred = std::array::from_fn(|c| blurred[c] + g * v[c]);
            }
            let plain = centred(Edge::Reflect101.index(j - r, w) as i64, y);
            blurred_sum = std::array::from_fn(|c| blurred_sum[c] + blurred[c]);
            plain_sum = std::array::from_fn(|c| plain_sum[c] + plain[c]);
            prefix[y as usize * extended + j as usize + 1] = blurred_sum;
            prefix[(h + y) as usize * extended + j as usize + 1] = plain_sum;
        }
    }
    let boxes = &params.boxes;
    let mut out = image.clone();
    for y in 0..h {
        for x in 0..w {
            let mut sum = [boxes.offset; 3];
            for b in &boxes.boxes[..boxes.count as usize] {
                let (dy, k, a, plane) = (b[0] as i64, b[1] as i64, b[2], b[3] as i64);
                let row = (plane + Edge::Reflect101.index(y + dy, h) as i64) as usize * extended;
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

    /// Adds the boxes, each spread by `gauss` along both axes, to a square of half side `radius`
    /// (zero taps, past a 3-tap Gaussian's reach, skipped).
    fn add_boxes(out: &mut [f64], radius: usize, boxes: &[RowBox], gauss: &[f64]) {
        let side = 2 * radius as i32 + 1;
        let reach = (gauss.len() / 2) as i32;
        for b in boxes {
            for x in -b.k..=b.k {
                for (ty, gy) in gauss.iter().enumerate() {
                    for (tx, gx) in gauss.iter().enumerate() {
                        if gx * gy == 0.0 {
                            continue;
                        }
                        let px = x + tx as i32 - reach + radius as i32;
                        let py = b.dy + ty as i32 - reach + radius as i32;
                        out[(py * side + px) as usize] += gx * gy * b.a as f64;
                    }
                }
            }
        }
    }

    #[test]
    fn split_rebuilds_the_kernel() {
        for &(radius, alias) in &RADIUS_ALIAS {
            let kernel = disk_kernel(radius, alias);
            let split = split_kernel(radius, alias);
            let side = 2 * split.radius + 1;
            let mut rebuilt = vec![0.0f64; side * side];
            add_boxes(&mut rebuilt, split.radius, &split.disk, &split.gauss);
            add_boxes(&mut rebuilt, split.radius, &split.correction, &[1.0]);
            let margin = split.radius - kernel.radius;
            let worst = (0..side * side)
                .map(|i| {
                    let (x, y) = (i % side, i / side);
                    let inside = (margin..side - margin).contains(&x)
                        && (margin..side - margin).contains(&y);
                    let expected = if inside {
                        let inner = 2 * kernel.radius + 1;
                        kernel.weights[(y - margin) * inner + x - margin]
                    } else {
                        0.0
                    };
                    (rebuilt[i] - expected).abs()
                })
                .fold(0.0, f64::max);
            assert!(worst < 2e-6, "radius {radius}: {worst}");
        }
    }

    #[test]
    fn disk_has_one_box_per_row_and_corrections_only_at_the_window_edge() {
        let counts: Vec<(usize, usize)> = RADIUS_ALIAS
            .iter()
            .map(|&(r, a)| {
                let split = split_kernel(r, a);
                (split.disk.len(), split.correction.len())
            })
            .collect();
        assert_eq!(counts[..3], [(7, 0), (9, 0), (13, 0)]);
        assert!(counts[3].1 > 0 && counts[4].1 > 0, "{counts:?}");
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
