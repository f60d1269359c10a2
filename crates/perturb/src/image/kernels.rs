//! Filter kernels shared by the blur-like corruptions (Gaussian, motion line, disk) and the
//! CPU-twin filters that apply them. Kernels are built on the CPU exactly as the reference
//! (SciPy / OpenCV / imagecorruptions) builds them and handed to the shaders in uniform buffers.

use crate::uniform_layout::{rust_layout, RustLayout, UniformLayout};

/// Mirrors `SUM_EPSILON` of `shaders/perturb/image/filter.wgsl`: added to a weighted sum before
/// truncating to 8 bits, so that f32 rounding does not drop flat regions by one level.
pub const SUM_EPSILON: f32 = 4e-6;

/// What an `Rgba8Unorm` texture holds after a shader stores `truncate8(v + SUM_EPSILON)`.
pub fn store_truncated(v: f32) -> f32 {
    (crate::image_f32::truncate8(v + SUM_EPSILON)) as f32 / 255.0
}

/// How a filter reads outside the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Edge {
    /// `aaa|abcd|ddd`: SciPy `nearest`, imagecorruptions' `shift`.
    Replicate,
    /// `cba|abcd|dcb`: SciPy `reflect` (half-sample symmetric).
    Reflect,
    /// `dcb|abcd|cba`: OpenCV `BORDER_REFLECT_101`, SciPy `mirror`.
    Reflect101,
}

impl Edge {
    /// The index inside `0..n` that position `i` reads (one reflection, enough for kernels
    /// shorter than the image).
    pub fn index(self, i: i64, n: i64) -> usize {
        let j = match self {
            Edge::Replicate => i.clamp(0, n - 1),
            Edge::Reflect if i < 0 => -1 - i,
            Edge::Reflect if i >= n => 2 * n - 1 - i,
            Edge::Reflect101 if i < 0 => -i,
            Edge::Reflect101 if i >= n => 2 * n - 2 - i,
            _ => i,
        };
        j.clamp(0, n - 1) as usize
    }
}

/// Half of SciPy's `gaussian_filter1d` kernel: weights for offsets 0..=radius with
/// radius = int(truncate·σ + 0.5), exp(−x²/2σ²) normalised over −radius..=radius.
pub fn gaussian_half_kernel(sigma: f64, truncate: f64) -> Vec<f32> {
    let radius = (truncate * sigma + 0.5) as i64;
    let raw: Vec<f64> = (0..=radius)
        .map(|x| (-0.5 * (x * x) as f64 / (sigma * sigma)).exp())
        .collect();
    let total = raw[0] + 2.0 * raw[1..].iter().sum::<f64>();
    raw.iter().map(|w| (w / total) as f32).collect()
}

/// Taps a [`Kernel1dUniform`] holds.
pub const KERNEL_1D_TAPS: usize = 256;

/// The uniform `Kernel1d` of `shaders/perturb/image/filter.wgsl`, built by [`symmetric_runs`].
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Kernel1dUniform {
    radius: i32,
    count: i32,
    /// `filter_rows.wgsl` / `filter_columns.wgsl`: 0 replicate, 1 reflect.
    edge: i32,
    _pad: i32,
    taps: [[f32; 4]; KERNEL_1D_TAPS],
}

impl Kernel1dUniform {
    const LAYOUT: RustLayout = rust_layout!(Kernel1dUniform {
        radius,
        count,
        edge,
        taps
    });

    /// Its layout as `struct Kernel1d` in `shader`.
    pub const fn layout(shader: &'static str) -> UniformLayout {
        UniformLayout {
            rust: Self::LAYOUT,
            wgsl: "Kernel1d",
            shader,
        }
    }
}

/// One tap of imagecorruptions' motion-blur line kernel: the output at (x, y) adds
/// `weight × input(x + dx, y + dy)` (edges replicated).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineTap {
    pub dx: i32,
    pub dy: i32,
    pub weight: f32,
}

/// imagecorruptions' `_motion_blur` kernel: 2·radius+1 taps along `angle_deg` with one-sided
/// Gaussian weights exp(−i²/2σ²) normalised; a tap whose shift reaches the image size ends the
/// kernel (without renormalising), as theirs does.
pub fn motion_line_taps(
    radius: u32,
    sigma: f64,
    angle_deg: f64,
    width: u32,
    height: u32,
) -> Vec<LineTap> {
    let taps = 2 * radius as usize + 1;
    let raw: Vec<f64> = (0..taps)
        .map(|i| (-((i * i) as f64) / (2.0 * sigma * sigma)).exp())
        .collect();
    let total: f64 = raw.iter().sum();
    let angle = angle_deg.to_radians();
    let (py, px) = (taps as f64 * angle.sin(), taps as f64 * angle.cos());
    let hypot = py.hypot(px);
    let mut out = Vec::with_capacity(taps);
    for (i, w) in raw.iter().enumerate() {
        // Their shift moves the image by (−ceil(i·p/|p| − ½)); reading the source at the
        // opposite offset is the same thing.
        let shift_y = -((i as f64 * py / hypot) - 0.5).ceil() as i64;
        let shift_x = -((i as f64 * px / hypot) - 0.5).ceil() as i64;
        if shift_y.abs() >= height as i64 || shift_x.abs() >= width as i64 {
            break;
        }
        out.push(LineTap {
            dx: -shift_x as i32,
            dy: -shift_y as i32,
            weight: (w / total) as f32,
        });
    }
    out
}

/// Taps a [`LineKernelUniform`] holds (radius ≤ 23).
pub const LINE_TAPS: usize = 48;

/// The uniform `LineKernel` of `shaders/perturb/image/filter.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LineKernelUniform {
    count: i32,
    _pad: [i32; 3],
    taps: [[f32; 4]; LINE_TAPS],
}

impl LineKernelUniform {
    const LAYOUT: RustLayout = rust_layout!(LineKernelUniform { count, taps });

    /// Its layout as `struct LineKernel` in `shader`.
    pub const fn layout(shader: &'static str) -> UniformLayout {
        UniformLayout {
            rust: Self::LAYOUT,
            wgsl: "LineKernel",
            shader,
        }
    }

    /// `None` when there are more than [`LINE_TAPS`] taps.
    pub fn new(taps: &[LineTap]) -> Option<Self> {
        let count = taps.len();
        if count > LINE_TAPS {
            return None;
        }
        let mut packed = [[0.0; 4]; LINE_TAPS];
        for (slot, t) in packed.iter_mut().zip(taps) {
            *slot = [t.dx as f32, t.dy as f32, t.weight, 0.0];
        }
        Some(Self {
            count: count as i32,
            _pad: [0; 3],
            taps: packed,
        })
    }
}

/// The uniform `Kernel1d` for runs of 8 outputs (see `filter.wgsl`): the weight at offset t in
/// slot t + radius + 8, `count` covering 2·radius + 8 source pixels. `edge` is read
/// by `filter_rows.wgsl` / `filter_columns.wgsl` (replicate or reflect).
pub fn symmetric_runs(half: &[f32], edge: Edge) -> Option<Kernel1dUniform> {
    let radius = half.len() - 1;
    let count = (2 * radius + 8).next_multiple_of(8);
    // The last iteration reads slots up to count + 7.
    if count + 8 > KERNEL_1D_TAPS {
        return None;
    }
    let mut taps = [[0.0; 4]; KERNEL_1D_TAPS];
    for (k, tap) in taps.iter_mut().skip(8).take(2 * radius + 1).enumerate() {
        tap[0] = half[k.abs_diff(radius)];
    }
    Some(Kernel1dUniform {
        radius: radius as i32,
        count: count as i32,
        edge: (edge == Edge::Reflect) as i32,
        _pad: 0,
        taps,
    })
}

/// Applies line taps to a plane of samples with edges replicated: the twin of the shaders'
/// line-kernel loop.
pub fn apply_line_taps<T: Sample>(
    plane: &[T],
    width: u32,
    height: u32,
    taps: &[LineTap],
) -> Vec<T> {
    let (w, h) = (width as i64, height as i64);
    let mut out = Vec::with_capacity(plane.len());
    for y in 0..h {
        for x in 0..w {
            let mut sum = T::zero();
            for t in taps {
                let sx = (x + t.dx as i64).clamp(0, w - 1);
                let sy = (y + t.dy as i64).clamp(0, h - 1);
                sum = sum.add_scaled(plane[(sy * w + sx) as usize], t.weight);
            }
            out.push(sum);
        }
    }
    out
}

/// A value a filter can sum: one channel or an RGB triple.
pub trait Sample: Copy {
    fn zero() -> Self;
    /// `self + weight · other`, channel by channel.
    fn add_scaled(self, other: Self, weight: f32) -> Self;
    fn map(self, f: impl Fn(f32) -> f32) -> Self;
}

impl Sample for f32 {
    fn zero() -> Self {
        0.0
    }
    fn add_scaled(self, other: Self, weight: f32) -> Self {
        self + weight * other
    }
    fn map(self, f: impl Fn(f32) -> f32) -> Self {
        f(self)
    }
}

impl Sample for [f32; 3] {
    fn zero() -> Self {
        [0.0; 3]
    }
    fn add_scaled(self, other: Self, weight: f32) -> Self {
        [0, 1, 2].map(|c| self[c] + weight * other[c])
    }
    fn map(self, f: impl Fn(f32) -> f32) -> Self {
        [f(self[0]), f(self[1]), f(self[2])]
    }
}

/// Which image axis a 1-D filter runs along.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    Rows,
    Columns,
}

/// A symmetric 1-D filter (`half[d]` at offsets ±d) along `axis`, summed over offsets in
/// ascending order as the shaders do.
pub fn symmetric_filter<T: Sample>(
    plane: &[T],
    width: u32,
    height: u32,
    half: &[f32],
    axis: Axis,
    edge: Edge,
) -> Vec<T> {
    let (w, h) = (width as i64, height as i64);
    let radius = half.len() as i64 - 1;
    let mut out = Vec::with_capacity(plane.len());
    for y in 0..h {
        for x in 0..w {
            let mut sum = T::zero();
            for t in -radius..=radius {
                let v = match axis {
                    Axis::Rows => plane[(y * w) as usize + edge.index(x + t, w)],
                    Axis::Columns => plane[edge.index(y + t, h) * w as usize + x as usize],
                };
                sum = sum.add_scaled(v, half[t.unsigned_abs() as usize]);
            }
            out.push(sum);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaussian_kernel_matches_scipy() {
        // scipy.ndimage._filters._gaussian_kernel1d(1.0, 0, 4): radius 4, centre 0.39894347.
        let k = gaussian_half_kernel(1.0, 4.0);
        assert_eq!(k.len(), 5);
        assert!((k[0] - 0.398_943_47).abs() < 1e-6, "{k:?}");
        assert!((k[1] - 0.241_970_5).abs() < 1e-6, "{k:?}");
        let total = k[0] + 2.0 * k[1..].iter().sum::<f32>();
        assert!((total - 1.0).abs() < 1e-6);
        // σ = 6 → radius int(24.5) = 24; σ = 0.7 → int(3.3) = 3.
        assert_eq!(gaussian_half_kernel(6.0, 4.0).len(), 25);
        assert_eq!(gaussian_half_kernel(0.7, 4.0).len(), 4);
    }

    #[test]
    fn edges_index_like_scipy_and_opencv() {
        let n = 4;
        let idx = |e: Edge| (-3..7).map(|i| e.index(i, n)).collect::<Vec<_>>();
        assert_eq!(idx(Edge::Replicate), [0, 0, 0, 0, 1, 2, 3, 3, 3, 3]);
        assert_eq!(idx(Edge::Reflect), [2, 1, 0, 0, 1, 2, 3, 3, 2, 1]);
        assert_eq!(idx(Edge::Reflect101), [3, 2, 1, 0, 1, 2, 3, 2, 1, 0]);
    }

    #[test]
    fn motion_taps_follow_the_angle() {
        // Angle 0: their shift moves the image by −i along x, so tap i reads x + i.
        let taps = motion_line_taps(2, 1.0, 0.0, 64, 64);
        assert_eq!(taps.len(), 5);
        for (i, t) in taps.iter().enumerate() {
            assert_eq!((t.dx, t.dy), (i as i32, 0));
        }
        let total: f32 = taps.iter().map(|t| t.weight).sum();
        assert!((total - 1.0).abs() < 1e-6);
        // Angle 90°: along y.
        let taps = motion_line_taps(2, 1.0, 90.0, 64, 64);
        assert!(taps
            .iter()
            .enumerate()
            .all(|(i, t)| t.dx == 0 && t.dy == i as i32));
        // A kernel longer than the image stops at the border, as imagecorruptions' does.
        assert_eq!(motion_line_taps(10, 3.0, 0.0, 8, 64).len(), 8);
    }

    #[test]
    fn symmetric_filter_preserves_constants_and_sums_correctly() {
        let plane = vec![0.5f32; 6 * 4];
        let half = gaussian_half_kernel(1.0, 4.0);
        for edge in [Edge::Replicate, Edge::Reflect, Edge::Reflect101] {
            for axis in [Axis::Rows, Axis::Columns] {
                let out = symmetric_filter(&plane, 6, 4, &half, axis, edge);
                assert!(out.iter().all(|v| (v - 0.5).abs() < 1e-6));
            }
        }
        // An impulse spreads into the kernel itself.
        let mut impulse = vec![0.0f32; 9];
        impulse[4] = 1.0;
        let out = symmetric_filter(&impulse, 9, 1, &[0.5, 0.25], Axis::Rows, Edge::Replicate);
        assert_eq!(out, [0.0, 0.0, 0.0, 0.25, 0.5, 0.25, 0.0, 0.0, 0.0]);
    }
}
