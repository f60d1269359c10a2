//! Tileable value noise and colour helpers for the procedural textures. Noise lattices wrap with
//! an integer period per texture, so every pattern repeats seamlessly.

use super::super::rng::{hash3, unit};

pub type Rgb = [f32; 3];

/// Value noise in [0, 1) at lattice coordinates (x, y), periodic with `period` cells on each axis.
pub fn value_noise(seed: u64, x: f32, y: f32, period: [u32; 2]) -> f32 {
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (smooth(x - x0), smooth(y - y0));
    let wrap = |i: f32, p: u32| (i as i64).rem_euclid(p.max(1) as i64);
    let (xa, xb) = (wrap(x0, period[0]), wrap(x0 + 1.0, period[0]));
    let (ya, yb) = (wrap(y0, period[1]), wrap(y0 + 1.0, period[1]));
    let l = |i, j| unit(hash3(seed, i, j, 0));
    let top = l(xa, ya) + (l(xb, ya) - l(xa, ya)) * fx;
    let bottom = l(xa, yb) + (l(xb, yb) - l(xa, yb)) * fx;
    top + (bottom - top) * fy
}

fn smooth(t: f32) -> f32 {
    t * t * (3.0 - 2.0 * t)
}

/// Fractal sum of `octaves` noise layers over texture coordinates (u, v) ∈ [0, 1), the first with
/// `cells` lattice cells per texture; result in [0, 1].
pub fn fbm(seed: u64, u: f32, v: f32, cells: [u32; 2], octaves: u32) -> f32 {
    let (mut sum, mut norm, mut amp) = (0.0, 0.0, 1.0);
    for o in 0..octaves {
        let p = [cells[0] << o, cells[1] << o];
        sum += amp
            * value_noise(
                seed.wrapping_add(o as u64),
                u * p[0] as f32,
                v * p[1] as f32,
                p,
            );
        norm += amp;
        amp *= 0.5;
    }
    sum / norm
}

/// Per-cell random value in [0, 1) for cell (i, j) and a purpose `k`.
pub fn cell(seed: u64, i: i64, j: i64, k: i64) -> f32 {
    unit(hash3(seed, i, j, k))
}

pub fn mix(a: Rgb, b: Rgb, t: f32) -> Rgb {
    let t = t.clamp(0.0, 1.0);
    std::array::from_fn(|c| a[c] + (b[c] - a[c]) * t)
}

pub fn scale(a: Rgb, k: f32) -> Rgb {
    a.map(|c| c * k)
}

/// Hue in turns, saturation and value in [0, 1].
pub fn hsv(h: f32, s: f32, v: f32) -> Rgb {
    let h6 = h.rem_euclid(1.0) * 6.0;
    let f = h6 - h6.floor();
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - s * f), v * (1.0 - s * (1.0 - f)));
    match h6 as u32 {
        0 => [v, t, p],
        1 => [q, v, p],
        2 => [p, v, t],
        3 => [p, q, v],
        4 => [t, p, v],
        _ => [v, p, q],
    }
}

/// 1 inside the band |x − centre| < half_width, else 0.
pub fn band(x: f32, centre: f32, half_width: f32) -> f32 {
    if (x - centre).abs() < half_width {
        1.0
    } else {
        0.0
    }
}

/// Distance to the nearest integer (0 on grid lines, 0.5 between them).
pub fn grid_distance(x: f32) -> f32 {
    (x - x.round()).abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_wraps_at_its_period() {
        for (x, y) in [(0.3, 0.7), (2.5, 1.25), (3.9, 0.01)] {
            let a = value_noise(9, x, y, [4, 2]);
            let b = value_noise(9, x + 4.0, y + 2.0, [4, 2]);
            assert!((a - b).abs() < 1e-6);
        }
        let (a, b) = (fbm(5, 0.0, 0.4, [3, 3], 4), fbm(5, 1.0, 0.4, [3, 3], 4));
        assert!((a - b).abs() < 1e-5, "fbm seam {a} vs {b}");
    }

    #[test]
    fn hsv_primaries() {
        let close = |a: Rgb, b: Rgb| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-5);
        assert!(close(hsv(0.0, 1.0, 1.0), [1.0, 0.0, 0.0]));
        assert!(close(hsv(1.0 / 3.0, 1.0, 1.0), [0.0, 1.0, 0.0]));
        assert!(close(hsv(0.5, 0.0, 0.5), [0.5, 0.5, 0.5]));
    }
}
