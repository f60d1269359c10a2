//! Hard surfaces: tiles, wallpaper, plaster, brick, ceiling tiles, marble, metal, foliage.

use std::f32::consts::TAU;

use super::noise::{cell, fbm, grid_distance, hsv, mix, scale, value_noise, Rgb};

/// 4 × 4 tiles per texture with grout, per-tile shade and speckle.
pub fn floor_tiles(seed: u64, u: f32, v: f32) -> Rgb {
    const N: f32 = 4.0;
    let (i, j) = ((u * N).floor() as i64, (v * N).floor() as i64);
    let base = [
        [0.82, 0.8, 0.76],
        [0.55, 0.53, 0.5],
        [0.7, 0.6, 0.5],
        [0.45, 0.5, 0.55],
    ][(cell(seed, 0, 0, 50) * 4.0) as usize];
    let checker = if cell(seed, 0, 0, 51) < 0.5 && (i + j).rem_euclid(2) == 1 {
        0.8
    } else {
        1.0
    };
    let tone = 0.88 + 0.2 * cell(seed, i.rem_euclid(4), j.rem_euclid(4), 52);
    let speckle = fbm(seed, u, v, [64, 64], 3);
    let vein = (1.0 - (fbm(seed ^ 9, u, v, [4, 4], 4) - 0.5).abs() * 20.0).max(0.0);
    if grid_distance(u * N) < 0.03 || grid_distance(v * N) < 0.03 {
        return [0.3, 0.29, 0.27];
    }
    scale(base, checker * tone * (0.87 + 0.2 * speckle - 0.15 * vein))
}

/// Paper with a faint half-drop repeat of flower motifs: a few per cent darker than its ground,
/// as in the matt, tone-on-tone papers of real rooms.
pub fn wallpaper(seed: u64, u: f32, v: f32) -> Rgb {
    let h = cell(seed, 0, 0, 60);
    let ground = hsv(h, 0.06 + 0.08 * cell(seed, 0, 0, 61), 0.88);
    let ink = scale(ground, 0.92);
    // Motif cells: 4 × 4, odd columns dropped by half a cell.
    let (cu, row) = (
        u * 4.0,
        v * 4.0
            + if ((u * 4.0).floor() as i64) % 2 == 1 {
                0.5
            } else {
                0.0
            },
    );
    let (x, y) = (cu.fract() - 0.5, row.fract() - 0.5);
    let (r, a) = ((x * x + y * y).sqrt(), y.atan2(x));
    let petals = 0.28 * (0.55 + 0.45 * (5.0 * a).cos());
    let c = if r < petals {
        mix(ink, ground, (r / petals).powi(3))
    } else {
        ground
    };
    scale(c, 0.985 + 0.03 * fbm(seed, u, v, [48, 48], 2))
}

/// Painted plaster: one paint colour, a faint roller mottle and a fine grain of a per cent or two.
pub fn plaster(seed: u64, u: f32, v: f32) -> Rgb {
    const PAINTS: [Rgb; 5] = [
        [0.93, 0.92, 0.89], // off-white
        [0.9, 0.86, 0.78],  // magnolia
        [0.84, 0.84, 0.82], // light grey
        [0.86, 0.88, 0.84], // pale sage
        [0.91, 0.88, 0.84], // warm white
    ];
    let base = PAINTS[(cell(seed, 0, 0, 70) * PAINTS.len() as f32) as usize];
    let mottle = fbm(seed, u, v, [6, 6], 4);
    let grain = value_noise(seed ^ 5, u * 256.0, v * 256.0, [256, 256]);
    scale(base, 0.97 + 0.04 * mottle + 0.02 * grain)
}

/// Running-bond brick, 4 bricks by 15 courses per texture.
pub fn brick(seed: u64, u: f32, v: f32) -> Rgb {
    const COURSES: f32 = 15.0;
    let course = (v * COURSES).floor() as i64;
    let shift = if course % 2 == 0 { 0.0 } else { 0.125 };
    let bu = (u + shift) * 4.0;
    let b = (bu.floor() as i64).rem_euclid(4);
    if grid_distance(v * COURSES) < 0.09 || grid_distance(bu) < 0.03 {
        return scale([0.72, 0.7, 0.66], 0.8 + 0.3 * fbm(seed, u, v, [64, 64], 2));
    }
    let base = mix(
        [0.6, 0.28, 0.2],
        [0.42, 0.22, 0.17],
        cell(seed, course, b, 80),
    );
    scale(base, 0.75 + 0.45 * fbm(seed ^ 2, u, v, [32, 32], 3))
}

/// 2 × 2 acoustic ceiling tiles with fissures and a metal grid.
pub fn ceiling_tiles(seed: u64, u: f32, v: f32) -> Rgb {
    if grid_distance(u * 2.0) < 0.012 || grid_distance(v * 2.0) < 0.012 {
        return [0.78, 0.78, 0.8];
    }
    let fissure = fbm(seed, u, v, [48, 48], 2);
    let dot = cell(seed, (u * 128.0) as i64, (v * 128.0) as i64, 90) > 0.88;
    let k = if dot { 0.86 } else { 0.92 } - if fissure < 0.3 { 0.05 } else { 0.0 };
    scale([0.95, 0.94, 0.9], k)
}

pub fn marble(seed: u64, u: f32, v: f32) -> Rgb {
    let dark = cell(seed, 0, 0, 100) < 0.3;
    let (ground, vein_col) = if dark {
        ([0.16, 0.2, 0.18], [0.75, 0.78, 0.74])
    } else {
        ([0.9, 0.89, 0.86], [0.35, 0.36, 0.4])
    };
    let t = fbm(seed, u, v, [4, 4], 5);
    let vein = ((u + v + 3.0 * t) * 3.0 * TAU).sin().abs().powf(0.25);
    scale(
        mix(mix(vein_col, ground, 0.6), ground, vein),
        0.9 + 0.15 * fbm(seed ^ 4, u, v, [32, 32], 2),
    )
}

pub fn brushed_metal(seed: u64, u: f32, v: f32) -> Rgb {
    let tone = [[0.62, 0.63, 0.66], [0.34, 0.34, 0.37], [0.8, 0.8, 0.8]]
        [(cell(seed, 0, 0, 110) * 3.0) as usize];
    scale(
        tone,
        0.3 + 0.8 * fbm(seed, u, v, [2, 256], 2) + 0.4 * fbm(seed ^ 1, u, v, [8, 8], 2),
    )
}

/// Overlapping leaves on a dark ground, 8 × 8 cells per texture.
pub fn leaves(seed: u64, u: f32, v: f32) -> Rgb {
    const N: i64 = 8;
    let mut c = [0.05, 0.12, 0.05];
    let (ci, cj) = ((u * N as f32).floor() as i64, (v * N as f32).floor() as i64);
    for dj in -1..=1 {
        for di in -1..=1 {
            let (i, j) = (ci + di, cj + dj);
            let (wi, wj) = (i.rem_euclid(N), j.rem_euclid(N));
            let cx = (i as f32 + cell(seed, wi, wj, 1)) / N as f32;
            let cy = (j as f32 + cell(seed, wi, wj, 2)) / N as f32;
            let angle = cell(seed, wi, wj, 3) * TAU;
            let (dx, dy) = ((u - cx) * N as f32, (v - cy) * N as f32);
            let (a, b) = (
                dx * angle.cos() + dy * angle.sin(),
                -dx * angle.sin() + dy * angle.cos(),
            );
            if (a / 0.9).powi(2) + (b / 0.35).powi(2) < 1.0 {
                let green = hsv(
                    0.25 + 0.1 * cell(seed, wi, wj, 4),
                    0.6,
                    0.35 + 0.35 * cell(seed, wi, wj, 5),
                );
                c = if b.abs() < 0.03 {
                    scale(green, 1.4)
                } else {
                    green
                };
            }
        }
    }
    c
}
