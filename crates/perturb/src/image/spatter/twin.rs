//! CPU twin of spatter's passes, step by step in the shaders' order.

use super::{Liquid, MUD_COLOR, NAME, PARAMS, TRUNCATE, WATER_COLOR};
use crate::image::kernels::{gaussian_half_kernel, symmetric_filter, Axis, Edge};
use crate::image_f32::{truncate8, RgbF32};
use crate::perturbation::FrameKey;
use crate::rng::normal_pair;

/// A single-channel plane with the shaders' edge rules.
struct Plane {
    width: i64,
    height: i64,
    data: Vec<f32>,
}

impl Plane {
    fn at(&self, x: i64, y: i64) -> f32 {
        self.data[(y * self.width + x) as usize]
    }

    fn clamped(&self, x: i64, y: i64) -> f32 {
        self.at(x.clamp(0, self.width - 1), y.clamp(0, self.height - 1))
    }

    fn reflected(&self, x: i64, y: i64) -> f32 {
        self.at(
            Edge::Reflect101.index(x, self.width) as i64,
            Edge::Reflect101.index(y, self.height) as i64,
        )
    }

    fn map(&self, f: impl Fn(i64, i64) -> f32) -> Plane {
        let data = (0..self.height)
            .flat_map(|y| (0..self.width).map(move |x| (x, y)))
            .map(|(x, y)| f(x, y))
            .collect();
        Plane {
            width: self.width,
            height: self.height,
            data,
        }
    }
}

/// The liquid layer: blurred noise with values under the threshold set to 0.
fn liquid_layer(width: u32, height: u32, key: &FrameKey) -> Plane {
    let (mean, deviation, sigma, threshold, _, _) = PARAMS[key.level()];
    let rng = key.rng(NAME, 0);
    let noise: Vec<f32> = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let bits = rng.draw([x, y, 0, 0]);
            mean + deviation * normal_pair(bits[0], bits[1])[0]
        })
        .collect();
    let half = gaussian_half_kernel(sigma, TRUNCATE);
    let rows = symmetric_filter(&noise, width, height, &half, Axis::Rows, Edge::Replicate);
    let blurred = symmetric_filter(&rows, width, height, &half, Axis::Columns, Edge::Replicate);
    Plane {
        width: width as i64,
        height: height as i64,
        data: blurred
            .into_iter()
            .map(|v| if v < threshold { 0.0 } else { v })
            .collect(),
    }
}

/// Canny classes (2 strong, 1 weak, 0 none), as `spatter_edges.wgsl`.
fn edge_classes(liquid: &Plane) -> Plane {
    let level = |x: i64, y: i64| (liquid.clamped(x, y) * 255.0).floor() as i32;
    let gradient = |x: i64, y: i64| {
        let l = |dx: i64, dy: i64| level(x + dx, y + dy);
        let gx = (l(1, -1) + 2 * l(1, 0) + l(1, 1)) - (l(-1, -1) + 2 * l(-1, 0) + l(-1, 1));
        let gy = (l(-1, 1) + 2 * l(0, 1) + l(1, 1)) - (l(-1, -1) + 2 * l(0, -1) + l(1, -1));
        (gx, gy)
    };
    let magnitude = |x: i64, y: i64| {
        if x < 0 || y < 0 || x >= liquid.width || y >= liquid.height {
            return 0;
        }
        let (gx, gy) = gradient(x, y);
        gx.abs() + gy.abs()
    };
    liquid.map(|x, y| {
        let (gx, gy) = gradient(x, y);
        let m = gx.abs() + gy.abs();
        if m <= 50 {
            return 0.0;
        }
        let (ax, ay) = (gx.abs(), gy.abs() << 15);
        let tg22x = ax * 13573;
        let maximum = if ay < tg22x {
            m > magnitude(x - 1, y) && m >= magnitude(x + 1, y)
        } else if ay > tg22x + (ax << 16) {
            m > magnitude(x, y - 1) && m >= magnitude(x, y + 1)
        } else {
            let s = if (gx ^ gy) < 0 { -1 } else { 1 };
            m > magnitude(x - s, y - 1) && m > magnitude(x + s, y + 1)
        };
        match (maximum, m > 150) {
            (false, _) => 0.0,
            (true, true) => 2.0,
            (true, false) => 1.0,
        }
    })
}

/// No edge within the truncation distance, as `spatter_squared_distance.wgsl`.
const NONE: u32 = 1024;
/// The truncation distance of the distance transform.
const REACH: i64 = 20;

/// Squared distance to the nearest edge pixel, NONE-capped, as `spatter_seeds`,
/// `spatter_column_distance` and `spatter_squared_distance` (columns, then rows).
fn squared_distances(classes: &Plane) -> Vec<u32> {
    let (w, h) = (classes.width, classes.height);
    let seeds: Vec<u32> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let class = classes.at(x, y);
            let near_strong = (-1..=1)
                .flat_map(|dy| (-1..=1).map(move |dx| (dx, dy)))
                .any(|(dx, dy)| classes.clamped(x + dx, y + dy) == 2.0);
            let edge = class == 2.0 || (class == 1.0 && near_strong);
            if edge {
                0
            } else {
                NONE
            }
        })
        .collect();
    // min over |d| ≤ REACH of d² + v at offset d along (dx, dy), inside the image.
    let pass = |v: &[u32], (dx, dy): (i64, i64)| -> Vec<u32> {
        (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                (-REACH..=REACH)
                    .filter_map(|d| {
                        let (qx, qy) = (x + d * dx, y + d * dy);
                        let inside = qx >= 0 && qy >= 0 && qx < w && qy < h;
                        inside.then(|| (d * d) as u32 + v[(qy * w + qx) as usize])
                    })
                    .fold(NONE, u32::min)
            })
            .collect()
    };
    pass(&pass(&seeds, (0, 1)), (1, 0))
}

/// cv2.equalizeHist's table.
fn equalisation(histogram: &[u32; 256]) -> [u32; 256] {
    let total: u32 = histogram.iter().sum();
    let mut lut = [0u32; 256];
    let first = histogram.iter().position(|&c| c > 0).unwrap_or(0).min(255);
    if histogram[first] == total {
        lut[first] = first as u32;
        return lut;
    }
    let scale = 255.0 / (total - histogram[first]) as f32;
    let mut sum = 0u32;
    for i in first + 1..256 {
        sum += histogram[i];
        lut[i] = ((sum as f32 * scale).round_ties_even()).clamp(0.0, 255.0) as u32;
    }
    lut
}

/// The water shading m (before normalisation), as passes 5–14.
fn water_shade(liquid: &Plane) -> Plane {
    let w = liquid.width;
    let squared = squared_distances(&edge_classes(liquid));
    let truncated = liquid.map(|x, y| {
        let d2 = squared[(y * w + x) as usize].min((REACH * REACH) as u32);
        (d2 as f32).sqrt()
    });
    let box_sum = |plane: &Plane, x: i64, y: i64| -> f32 {
        (-1..=1)
            .flat_map(|dy| (-1..=1).map(move |dx| (dx, dy)))
            .map(|(dx, dy)| plane.reflected(x + dx, y + dy))
            .sum()
    };
    let distance = truncated.map(|x, y| (box_sum(&truncated, x, y) / 9.0).floor());
    let mut histogram = [0u32; 256];
    for v in &distance.data {
        histogram[*v as usize] += 1;
    }
    let lut = equalisation(&histogram);
    let equalised = |x: i64, y: i64| lut[distance.reflected(x, y) as usize] as i32;
    let embossed = distance.map(|x, y| {
        let e = -2 * equalised(x - 1, y - 1) - equalised(x, y - 1) - equalised(x - 1, y)
            + equalised(x, y)
            + equalised(x + 1, y)
            + equalised(x, y + 1)
            + 2 * equalised(x + 1, y + 1);
        e.clamp(0, 255) as f32
    });
    embossed.map(|x, y| {
        let shade = (box_sum(&embossed, x, y) / 9.0).round_ties_even();
        (liquid.at(x, y) * 255.0).floor() * shade
    })
}

/// CPU twin of spatter.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let (_, _, _, threshold, intensity, kind) = PARAMS[key.level()];
    let (w, h) = (image.width, image.height);
    let liquid = liquid_layer(w, h, key);
    let mut out = image.clone();
    match kind {
        Liquid::Water => {
            let shade = water_shade(&liquid);
            let top = shade.data.iter().copied().fold(0.0, f32::max);
            for (i, p) in out.data.iter_mut().enumerate() {
                let m = if top > 0.0 {
                    shade.data[i] / top * intensity
                } else {
                    0.0
                };
                *p = std::array::from_fn(|c| truncate8(p[c] + m * WATER_COLOR[c]) as f32 / 255.0);
            }
        }
        Liquid::Mud => {
            let mask: Vec<f32> = liquid
                .data
                .iter()
                .map(|&v| if v > threshold { 1.0 } else { 0.0 })
                .collect();
            let half = gaussian_half_kernel(intensity as f64, TRUNCATE);
            let rows = symmetric_filter(&mask, w, h, &half, Axis::Rows, Edge::Replicate);
            let m = symmetric_filter(&rows, w, h, &half, Axis::Columns, Edge::Replicate);
            for (i, p) in out.data.iter_mut().enumerate() {
                let m = if m[i] < 0.8 { 0.0 } else { m[i] };
                *p = std::array::from_fn(|c| {
                    truncate8(p[c] * (1.0 - m) + m * MUD_COLOR[c]) as f32 / 255.0
                });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equalisation_spreads_levels_like_opencv() {
        let mut histogram = [0u32; 256];
        histogram[3] = 10;
        histogram[5] = 30;
        histogram[20] = 60;
        let lut = equalisation(&histogram);
        // first occupied level → 0; then cumulative counts × 255 / (100 − 10).
        assert_eq!((lut[3], lut[5], lut[20]), (0, 85, 255));
        let mut flat = [0u32; 256];
        flat[20] = 7;
        assert_eq!(equalisation(&flat)[20], 20);
    }

    #[test]
    fn droplets_are_blobs_with_rims_not_noise() {
        // Severity 1: the liquid layer covers a minority of the frame in connected blobs (a
        // pixel's liquid neighbours are mostly liquid too), and edges trace their outlines.
        let liquid = liquid_layer(160, 120, &crate::testing::key(3, 1));
        let wet: Vec<bool> = liquid.data.iter().map(|&v| v > 0.0).collect();
        let fraction = wet.iter().filter(|&&b| b).count() as f32 / wet.len() as f32;
        assert!((0.02..0.5).contains(&fraction), "wet fraction {fraction}");
        let (mut same, mut pairs) = (0, 0);
        for y in 0..120 {
            for x in 0..159 {
                if wet[y * 160 + x] {
                    pairs += 1;
                    same += wet[y * 160 + x + 1] as u32;
                }
            }
        }
        assert!(
            same as f32 / pairs as f32 > 0.8,
            "blobs, not speckle: {same}/{pairs}"
        );
        let edges = edge_classes(&liquid);
        let outline = edges.data.iter().filter(|&&c| c == 2.0).count();
        assert!(outline > 0);
        assert!((outline as f32) < 0.5 * wet.iter().filter(|&&b| b).count() as f32);
    }
}
