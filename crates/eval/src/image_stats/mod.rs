//! Image statistics a person can set beside real data to judge how realistic rendered frames
//! are: FAST corners at ORB-SLAM's threshold and how strong they are, local contrast, the
//! distribution of gradient magnitudes, colour saturation and the share of low-texture cells.

mod contrast;
mod fast;
mod target;

use rslam_core::RgbImage;
use serde::Serialize;

pub use contrast::{block_contrasts, BLOCK};
pub use fast::{corners, Corner, ORB_SLAM_MIN_THRESHOLD, ORB_SLAM_THRESHOLD};
pub use target::{Band, RealPhotographs, REAL_PHOTOGRAPHS};

/// A corner at least this strong stays a corner at [`ORB_SLAM_MIN_THRESHOLD`] when the image's
/// contrast is cut to a fifth (contrast at severity 3 scales deviations from the mean by 0.2).
pub const STRONG_CORNER: u8 = 5 * ORB_SLAM_MIN_THRESHOLD;

/// Side of the square image cells, pixels (ORB-SLAM's extractor grid is 30 px).
pub const CELL: usize = 32;
/// A cell whose mean gradient magnitude (grey levels per pixel, Sobel / 8) is below this holds no
/// texture a feature tracker could use.
pub const LOW_TEXTURE_GRADIENT: f32 = 2.0;

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FrameStats {
    /// FAST-9 corners at [`ORB_SLAM_THRESHOLD`] after non-maximum suppression.
    pub fast_corners: usize,
    /// FAST-9 corners at [`ORB_SLAM_MIN_THRESHOLD`], per 10,000 pixels (resolutions compare).
    pub weak_corner_density: f32,
    /// Strength of those corners (grey levels): median and 90th percentile; 0 without corners.
    pub corner_strength_p50: f32,
    pub corner_strength_p90: f32,
    /// Share of those corners at least [`STRONG_CORNER`] strong.
    pub strong_corners: f32,
    /// Local contrast ([`block_contrasts`], grey levels): 10th, 50th and 90th percentiles.
    pub contrast_p10: f32,
    pub contrast_p50: f32,
    pub contrast_p90: f32,
    /// Gradient magnitude (grey levels per pixel): median and 90th percentile over the pixels.
    pub gradient_p50: f32,
    pub gradient_p90: f32,
    /// Mean HSV saturation, 0–1.
    pub saturation: f32,
    /// Share of [`CELL`]-pixel cells whose mean gradient is below [`LOW_TEXTURE_GRADIENT`].
    pub low_texture_cells: f32,
}

/// Grey levels (BT.601 luma) of an sRGB image.
fn grey(image: &RgbImage) -> Vec<u8> {
    image
        .data
        .chunks_exact(3)
        .map(|p| ((299 * p[0] as u32 + 587 * p[1] as u32 + 114 * p[2] as u32 + 500) / 1000) as u8)
        .collect()
}

/// Sobel gradient magnitude / 8 (grey levels per pixel); 0 on the border.
fn gradient_magnitude(g: &[u8], w: usize, h: usize) -> Vec<f32> {
    let mut out = vec![0.0; w * h];
    for y in 1..h.saturating_sub(1) {
        for x in 1..w - 1 {
            let p = |dx: i32, dy: i32| {
                g[(y as i32 + dy) as usize * w + (x as i32 + dx) as usize] as f32
            };
            let gx = (p(1, -1) + 2.0 * p(1, 0) + p(1, 1)) - (p(-1, -1) + 2.0 * p(-1, 0) + p(-1, 1));
            let gy = (p(-1, 1) + 2.0 * p(0, 1) + p(1, 1)) - (p(-1, -1) + 2.0 * p(0, -1) + p(1, -1));
            out[y * w + x] = (gx * gx + gy * gy).sqrt() / 8.0;
        }
    }
    out
}

/// The share of `values` that `keep` holds for; 0 when there are none.
fn share(values: &[f32], keep: impl Fn(f32) -> bool) -> f32 {
    if values.is_empty() {
        return 0.0;
    }
    values.iter().filter(|&&v| keep(v)).count() as f32 / values.len() as f32
}

fn percentile(sorted: &[f32], q: f32) -> f32 {
    if sorted.is_empty() {
        return 0.0;
    }
    sorted[((sorted.len() - 1) as f32 * q).round() as usize]
}

pub fn frame_stats(image: &RgbImage) -> FrameStats {
    let (w, h) = (image.width as usize, image.height as usize);
    let g = grey(image);
    let grad = gradient_magnitude(&g, w, h);
    let mut sorted = grad.clone();
    sorted.sort_by(f32::total_cmp);
    let saturation = image
        .data
        .chunks_exact(3)
        .map(|p| {
            let (max, min) = (
                p.iter().max().copied().unwrap_or(0),
                p.iter().min().copied().unwrap_or(0),
            );
            if max == 0 {
                0.0
            } else {
                (max - min) as f32 / max as f32
            }
        })
        .sum::<f32>()
        / (w * h).max(1) as f32;
    let (mut cells, mut low) = (0usize, 0usize);
    for cy in 0..h / CELL {
        for cx in 0..w / CELL {
            let sum: f32 = (0..CELL)
                .flat_map(|y| (0..CELL).map(move |x| (cx * CELL + x, cy * CELL + y)))
                .map(|(x, y)| grad[y * w + x])
                .sum();
            cells += 1;
            if sum / (CELL * CELL) as f32 <= LOW_TEXTURE_GRADIENT {
                low += 1;
            }
        }
    }
    // A corner beaten in suppression is beaten by a stronger neighbour, so the corners at the
    // higher threshold are exactly those at the lower one that are stronger than it.
    let weak = corners(&g, w, h, ORB_SLAM_MIN_THRESHOLD);
    let mut strengths: Vec<f32> = weak.iter().map(|c| c.strength as f32).collect();
    strengths.sort_by(f32::total_cmp);
    let mut contrasts = block_contrasts(&g, w, h);
    contrasts.sort_by(f32::total_cmp);
    FrameStats {
        fast_corners: weak
            .iter()
            .filter(|c| c.strength > ORB_SLAM_THRESHOLD)
            .count(),
        weak_corner_density: weak.len() as f32 * 1e4 / (w * h).max(1) as f32,
        corner_strength_p50: percentile(&strengths, 0.5),
        corner_strength_p90: percentile(&strengths, 0.9),
        strong_corners: share(&strengths, |s| s >= STRONG_CORNER as f32),
        contrast_p10: percentile(&contrasts, 0.1),
        contrast_p50: percentile(&contrasts, 0.5),
        contrast_p90: percentile(&contrasts, 0.9),
        gradient_p50: percentile(&sorted, 0.5),
        gradient_p90: percentile(&sorted, 0.9),
        saturation,
        low_texture_cells: if cells == 0 {
            0.0
        } else {
            low as f32 / cells as f32
        },
    }
}

/// 10th, 50th and 90th percentiles of one statistic over a sequence's frames.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Spread {
    pub p10: f32,
    pub p50: f32,
    pub p90: f32,
}

impl Spread {
    pub fn of(values: impl Iterator<Item = f32>) -> Self {
        let mut v: Vec<f32> = values.collect();
        v.sort_by(f32::total_cmp);
        Self {
            p10: percentile(&v, 0.1),
            p50: percentile(&v, 0.5),
            p90: percentile(&v, 0.9),
        }
    }
}

/// The statistics of a sequence: the spread of each over its frames.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SequenceStats {
    pub frames: usize,
    pub fast_corners: Spread,
    pub weak_corner_density: Spread,
    pub corner_strength_p50: Spread,
    pub strong_corners: Spread,
    pub contrast_p10: Spread,
    pub contrast_p50: Spread,
    pub contrast_p90: Spread,
    pub gradient_p50: Spread,
    pub gradient_p90: Spread,
    pub saturation: Spread,
    pub low_texture_cells: Spread,
}

impl SequenceStats {
    pub fn of(frames: &[FrameStats]) -> Self {
        Self {
            frames: frames.len(),
            fast_corners: Spread::of(frames.iter().map(|f| f.fast_corners as f32)),
            weak_corner_density: Spread::of(frames.iter().map(|f| f.weak_corner_density)),
            corner_strength_p50: Spread::of(frames.iter().map(|f| f.corner_strength_p50)),
            strong_corners: Spread::of(frames.iter().map(|f| f.strong_corners)),
            contrast_p10: Spread::of(frames.iter().map(|f| f.contrast_p10)),
            contrast_p50: Spread::of(frames.iter().map(|f| f.contrast_p50)),
            contrast_p90: Spread::of(frames.iter().map(|f| f.contrast_p90)),
            gradient_p50: Spread::of(frames.iter().map(|f| f.gradient_p50)),
            gradient_p90: Spread::of(frames.iter().map(|f| f.gradient_p90)),
            saturation: Spread::of(frames.iter().map(|f| f.saturation)),
            low_texture_cells: Spread::of(frames.iter().map(|f| f.low_texture_cells)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::image;

    #[test]
    fn a_flat_grey_image_is_all_low_texture_with_no_corners_or_saturation() {
        let s = frame_stats(&image(128, 96, |_, _| [120, 120, 120]));
        assert_eq!(s.fast_corners, 0);
        assert_eq!((s.weak_corner_density, s.corner_strength_p90), (0.0, 0.0));
        assert_eq!((s.contrast_p10, s.contrast_p90), (0.0, 0.0));
        assert_eq!(s.gradient_p90, 0.0);
        assert_eq!(s.saturation, 0.0);
        assert_eq!(s.low_texture_cells, 1.0);
    }

    #[test]
    fn separate_squares_have_corners_texture_everywhere_and_edge_gradients() {
        // 8-pixel squares of grey 200 every 16 pixels on black: four corners each; the Sobel
        // magnitude / 8 across an edge is 4 · 200 / 8 = 100 on the two pixels beside it.
        let s = frame_stats(&image(128, 128, |x, y| {
            let v = if x % 16 < 8 && y % 16 < 8 { 200 } else { 0 };
            [v, v, v]
        }));
        // 64 squares, less the corners of the first row and column in the 3-pixel border FAST
        // leaves out: 49 whole squares, 14 with two corners, one with one.
        assert_eq!(s.fast_corners, 49 * 4 + 14 * 2 + 1);
        let weak = s.weak_corner_density * 128.0 * 128.0 / 1e4;
        assert!((weak - s.fast_corners as f32).abs() < 1e-3, "{weak}");
        assert_eq!((s.corner_strength_p50, s.strong_corners), (200.0, 1.0));
        // The squares fill whole 8 × 8 blocks: no block holds two grey levels.
        assert_eq!(s.contrast_p90, 0.0);
        assert_eq!(s.low_texture_cells, 0.0);
        assert_eq!(
            s.gradient_p50, 0.0,
            "most pixels are inside or between squares"
        );
        assert!(s.gradient_p90 >= 70.0, "{}", s.gradient_p90);
    }

    #[test]
    fn a_sequence_summary_takes_percentiles_over_frames() {
        let frames: Vec<FrameStats> = (0..=10)
            .map(|i| FrameStats {
                fast_corners: 10 * i,
                weak_corner_density: i as f32,
                corner_strength_p50: i as f32,
                corner_strength_p90: i as f32,
                strong_corners: 0.1 * i as f32,
                contrast_p10: i as f32,
                contrast_p50: i as f32,
                contrast_p90: i as f32,
                gradient_p50: i as f32,
                gradient_p90: 2.0 * i as f32,
                saturation: 0.05 * i as f32,
                low_texture_cells: 0.1 * i as f32,
            })
            .collect();
        let s = SequenceStats::of(&frames);
        assert_eq!(s.frames, 11);
        assert_eq!(
            (s.fast_corners.p10, s.fast_corners.p50, s.fast_corners.p90),
            (10.0, 50.0, 90.0)
        );
        assert_eq!(s.gradient_p90.p50, 10.0);
    }

    #[test]
    fn pure_red_is_fully_saturated() {
        let s = frame_stats(&image(64, 64, |_, _| [255, 0, 0]));
        assert_eq!(s.saturation, 1.0);
    }
}
