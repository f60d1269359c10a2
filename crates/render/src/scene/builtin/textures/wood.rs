//! Wood: floor planks, furniture grain, panelled doors.

use std::f32::consts::TAU;

use super::noise::{cell, fbm, grid_distance, mix, scale, Rgb};

const WOODS: [Rgb; 5] = [
    [0.74, 0.54, 0.33], // oak
    [0.46, 0.31, 0.19], // walnut
    [0.85, 0.72, 0.53], // ash
    [0.64, 0.38, 0.24], // cherry
    [0.66, 0.61, 0.54], // grey-washed
];

fn palette(seed: u64) -> Rgb {
    WOODS[(cell(seed, 0, 0, 99) * WOODS.len() as f32) as usize]
}

/// Grain streaks along u with growth rings; `rings` rings per texture along v.
fn grain_shade(seed: u64, u: f32, v: f32, rings: u32) -> f32 {
    let streak = fbm(seed, u, v, [2, 48], 3);
    let warp = fbm(seed ^ 0x51, u, v, [2, 4], 2);
    let ring = (TAU * (v * rings as f32 + 3.0 * warp)).sin() * 0.5 + 0.5;
    0.8 + 0.3 * streak - 0.15 * ring.powi(4)
}

/// Eight rows of staggered planks per tile, dark seams between them.
pub fn floor_planks(seed: u64, u: f32, v: f32) -> Rgb {
    const ROWS: f32 = 8.0;
    let row = (v * ROWS).floor() as i64;
    let offset = cell(seed, row, 0, 1);
    let along = (u + offset) * 2.0;
    let plank = (along.floor() as i64).rem_euclid(2);
    let plank_seed = seed ^ ((row as u64 * 31 + plank as u64 + 1) * 0x9e37_79b9);
    let tone = 0.9 + 0.15 * cell(seed, row, plank, 2);
    let base = mix(
        palette(seed),
        [0.55, 0.4, 0.28],
        cell(seed, row, plank, 3) * 0.3,
    );
    let mut c = scale(base, tone * grain_shade(plank_seed, u, v, 96));
    let seam_row = grid_distance(v * ROWS) < 0.035;
    let seam_joint = grid_distance(along) < 0.006;
    if seam_row || seam_joint {
        c = scale(c, 0.6);
    }
    c
}

/// Furniture wood: grain along u.
pub fn grain(seed: u64, u: f32, v: f32) -> Rgb {
    let knot_u = cell(seed, 1, 0, 0);
    let knot_v = cell(seed, 2, 0, 0);
    let d = ((u - knot_u).powi(2) * 4.0 + (v - knot_v).powi(2) * 16.0).sqrt();
    let knot = (1.0 - d * 12.0).clamp(0.0, 1.0);
    scale(
        palette(seed),
        grain_shade(seed, u, v, 40) * (1.0 - 0.45 * knot),
    )
}

/// A panelled door (fit to the door leaf): two columns of three panels, painted or wooden.
pub fn door(seed: u64, u: f32, v: f32) -> Rgb {
    let painted = cell(seed, 0, 0, 5) < 0.5;
    let base = if painted {
        mix([0.93, 0.92, 0.88], [0.55, 0.62, 0.68], cell(seed, 0, 0, 6))
    } else {
        palette(seed)
    };
    let texture = if painted {
        0.93 + 0.07 * fbm(seed, u, v, [8, 16], 3)
    } else {
        grain_shade(seed, v, u, 24)
    };
    let mut c = scale(base, texture);
    // Panels: columns at u ∈ [0.12, 0.46] and [0.54, 0.88]; rows split v ∈ [0.06, 0.94] in three.
    let col = if (0.12..0.46).contains(&u) {
        Some((u - 0.12) / 0.34)
    } else if (0.54..0.88).contains(&u) {
        Some((u - 0.54) / 0.34)
    } else {
        None
    };
    let row_v = (v - 0.06) / 0.88 * 3.0;
    if let (Some(pu), true) = (col, (0.0..3.0).contains(&row_v)) {
        let pv = row_v.fract();
        let inset = !(0.06..=0.94).contains(&pv);
        if !inset {
            let edge = pu.min(1.0 - pu).min(pv.min(1.0 - pv) * 0.3);
            if edge < 0.06 {
                // Bevel: lit from above-left.
                c = scale(c, if pu < 0.5 && pv < 0.5 { 1.12 } else { 0.72 });
            } else {
                c = scale(c, 0.93);
            }
        }
    }
    if (0.79..0.86).contains(&u) && (0.5..0.56).contains(&v) {
        c = [0.75, 0.7, 0.55]; // lock plate
    }
    c
}
