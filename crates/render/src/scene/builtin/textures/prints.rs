//! Printed and displayed things, each fitted to one face: posters, paintings, book spines,
//! cardboard, screens, whiteboards, the view through a window, keyboards; plus page edges.

use std::f32::consts::TAU;

use super::super::rng::{hash3, unit};
use super::noise::{cell, fbm, grid_distance, hsv, mix, scale, Rgb};
use crate::scene::srgb::{linear_to_srgb, unit_srgb_to_linear};

/// Blocky text: 3 × 5 glyphs from hash bits, words separated by blanks, ragged line ends.
fn text_ink(seed: u64, x: f32, y: f32, glyph_w: f32, line_h: f32, line_len: f32) -> bool {
    let (gx, gy) = ((x / glyph_w).floor(), (y / line_h).floor());
    let (fx, fy) = (x / glyph_w - gx, y / line_h - gy);
    if x < 0.0 || y < 0.0 || fx > 0.75 || !(0.2..0.8).contains(&fy) {
        return false;
    }
    if x > line_len * (0.55 + 0.45 * cell(seed, 0, gy as i64, 7)) {
        return false;
    }
    let id = hash3(seed, gx as i64, gy as i64, 1);
    if unit(id) < 0.17 {
        return false;
    }
    let (bx, by) = ((fx / 0.75 * 3.0) as u64, ((fy - 0.2) / 0.6 * 5.0) as u64);
    (id >> (8 + by * 3 + bx)) & 1 == 1
}

fn inside(u: f32, v: f32, rect: [f32; 4]) -> bool {
    (rect[0]..rect[2]).contains(&u) && (rect[1]..rect[3]).contains(&v)
}

fn segment_distance(p: [f32; 2], a: [f32; 2], b: [f32; 2]) -> f32 {
    let (ab, ap) = ([b[0] - a[0], b[1] - a[1]], [p[0] - a[0], p[1] - a[1]]);
    let t = ((ap[0] * ab[0] + ap[1] * ab[1]) / (ab[0] * ab[0] + ab[1] * ab[1]).max(1e-9))
        .clamp(0.0, 1.0);
    ((ap[0] - t * ab[0]).powi(2) + (ap[1] - t * ab[1]).powi(2)).sqrt()
}

/// Fine page edges, tiling.
pub fn pages(seed: u64, u: f32, v: f32) -> Rgb {
    let line = ((v * 160.0).fract() < 0.3) as u8 as f32;
    scale(
        [0.93, 0.9, 0.82],
        0.9 - 0.12 * line + 0.08 * fbm(seed, u, v, [16, 4], 2),
    )
}

/// Shapes on a coloured ground, a title and a column of body text.
pub fn poster(seed: u64, u: f32, v: f32) -> Rgb {
    let h = cell(seed, 0, 0, 1);
    let light = cell(seed, 0, 0, 2) < 0.6;
    let ground = if light {
        hsv(h, 0.15, 0.92)
    } else {
        hsv(h, 0.6, 0.3)
    };
    let ink = if light {
        [0.1, 0.1, 0.12]
    } else {
        [0.95, 0.93, 0.85]
    };
    let mut c = ground;
    for k in 0..6 {
        let (cx, cy) = (cell(seed, k, 0, 3), 0.15 + 0.45 * cell(seed, k, 0, 4));
        let r = 0.06 + 0.16 * cell(seed, k, 0, 5);
        let colour = hsv(h + 0.2 * k as f32 + cell(seed, k, 0, 6) * 0.3, 0.7, 0.85);
        let (dx, dy) = (u - cx, v - cy);
        let hit = match k % 3 {
            0 => dx * dx + dy * dy < r * r,
            1 => dx.abs() < r && dy.abs() < r * 0.6,
            _ => dy > -r && dy < r && dx.abs() < (dy + r) * 0.5,
        };
        if hit {
            c = colour;
        }
    }
    if grid_distance(u * 20.0 + v * 20.0) < 0.08 && v < 0.65 && cell(seed, 0, 0, 8) < 0.4 {
        c = scale(c, 0.8);
    }
    let title = text_ink(seed, u - 0.08, v - 0.7, 0.055, 0.085, 0.84);
    let body = v > 0.87 && text_ink(seed ^ 1, u - 0.08, v - 0.87, 0.016, 0.022, 0.84);
    if title || body {
        c = ink;
    }
    if !(0.03..=0.97).contains(&u) || !(0.03..=0.97).contains(&v) {
        c = [0.97, 0.97, 0.95];
    }
    c
}

/// A landscape (sky, clouds, mountains, hills, trees, lake) or a grid abstraction.
pub fn painting(seed: u64, u: f32, v: f32) -> Rgb {
    let brush = 0.9 + 0.2 * fbm(seed ^ 3, u, v, [48, 48], 2);
    if cell(seed, 0, 0, 1) < 0.35 {
        return scale(abstract_grid(seed, u, v), brush);
    }
    let ridge = 0.35 + 0.2 * fbm(seed, u, 0.0, [5, 1], 4);
    let hill = 0.55 + 0.12 * fbm(seed ^ 1, u, 0.5, [3, 1], 3);
    let sun = (u - 0.2 - 0.6 * cell(seed, 0, 0, 2)).powi(2) + (v - 0.18).powi(2) < 0.004;
    let c = if v < ridge {
        let sky = mix([0.35, 0.55, 0.85], [0.95, 0.8, 0.6], v / ridge);
        if sun {
            [1.0, 0.92, 0.6]
        } else if fbm(seed ^ 2, u, v * 2.0, [6, 3], 4) > 0.58 {
            [0.97, 0.96, 0.94]
        } else {
            sky
        }
    } else if v < hill {
        let snow = v < ridge + 0.03;
        if snow {
            [0.92, 0.93, 0.96]
        } else {
            mix([0.42, 0.45, 0.55], [0.3, 0.33, 0.4], (v - ridge) * 5.0)
        }
    } else if v < 0.78 {
        let tree = fbm(seed ^ 5, u, v, [24, 12], 2) > 0.55;
        if tree {
            [0.1, 0.25, 0.1]
        } else {
            mix([0.35, 0.55, 0.25], [0.25, 0.4, 0.15], (v - hill) * 4.0)
        }
    } else {
        let ripple = ((v * 90.0 + 2.0 * fbm(seed ^ 6, u, v, [8, 4], 2)) * TAU).sin() * 0.5 + 0.5;
        mix([0.2, 0.35, 0.55], [0.55, 0.7, 0.85], ripple * 0.6)
    };
    scale(c, brush)
}

fn abstract_grid(seed: u64, u: f32, v: f32) -> Rgb {
    let cuts = |axis: i64, x: f32| -> (bool, i64) {
        let mut index = 0;
        for k in 0..4 {
            let at = 0.15 + 0.7 * cell(seed, axis, k, 10);
            if (x - at).abs() < 0.012 {
                return (true, 0);
            }
            if x > at {
                index += 1 << k;
            }
        }
        (false, index)
    };
    let (line_u, iu) = cuts(0, u);
    let (line_v, iv) = cuts(1, v);
    if line_u || line_v {
        return [0.08, 0.08, 0.08];
    }
    let pick = cell(seed, iu, iv, 11);
    if pick < 0.55 {
        [0.93, 0.92, 0.88]
    } else {
        [
            [0.85, 0.15, 0.12],
            [0.1, 0.25, 0.65],
            [0.95, 0.8, 0.15],
            [0.2, 0.2, 0.2],
        ][((pick - 0.55) / 0.45 * 4.0) as usize % 4]
    }
}

/// A book spine (u across, v along the book): light cloth with bands and a vertical title; the
/// book's colour comes from its vertex tint.
pub fn book_spine(seed: u64, u: f32, v: f32) -> Rgb {
    let cloth = 0.85 + 0.15 * fbm(seed, u, v, [8, 32], 2);
    let band_at = 0.06 + 0.06 * cell(seed, 0, 0, 1);
    if (v - band_at).abs() < 0.015 || (v - (1.0 - band_at)).abs() < 0.015 {
        return [0.25, 0.22, 0.15];
    }
    if (0.2..0.8).contains(&u) && text_ink(seed, v - 0.22, u - 0.2, 0.06, 0.6, 0.5) {
        return [0.15, 0.13, 0.1];
    }
    if (0.78..0.88).contains(&v) && (0.25..0.75).contains(&u) {
        return [0.95, 0.93, 0.85];
    }
    scale([0.95, 0.95, 0.95], cloth)
}

/// A cardboard box face: fibres, tape across, a label and "this way up" arrows.
pub fn cardboard(seed: u64, u: f32, v: f32) -> Rgb {
    let mut c = scale([0.7, 0.54, 0.36], 0.85 + 0.25 * fbm(seed, u, v, [4, 64], 3));
    if (v - 0.5).abs() < 0.06 {
        c = scale([0.78, 0.64, 0.45], 0.95 + 0.05 * ((u * 300.0).sin()));
    }
    let label = [
        0.1 + 0.4 * cell(seed, 0, 0, 1),
        0.62,
        0.48 + 0.4 * cell(seed, 0, 0, 1),
        0.9,
    ];
    if inside(u, v, label) {
        c = [0.96, 0.96, 0.94];
        if text_ink(
            seed,
            u - label[0] - 0.02,
            v - label[1] - 0.03,
            0.025,
            0.05,
            0.34,
        ) {
            c = [0.1, 0.1, 0.1];
        }
    }
    for ax in [0.12, 0.22] {
        let shaft = (u - ax).abs() < 0.012 && (0.1..0.3).contains(&v);
        let head = v > 0.08 && v < 0.15 && (u - ax).abs() < (v - 0.08) * 0.6;
        if shaft || head {
            c = [0.15, 0.12, 0.1];
        }
    }
    c
}

/// A desktop: wallpaper, two or three windows of coloured text, a taskbar.
pub fn screen(seed: u64, u: f32, v: f32) -> Rgb {
    let dark = cell(seed, 0, 0, 1) < 0.5;
    let mut c = mix(
        hsv(cell(seed, 0, 0, 2), 0.5, 0.55),
        hsv(cell(seed, 0, 0, 3), 0.6, 0.3),
        v,
    );
    if v > 0.94 {
        c = [0.12, 0.13, 0.15];
        if grid_distance(u * 24.0) > 0.3 && (0.955..0.985).contains(&v) && u < 0.4 {
            c = hsv(u * 3.0, 0.5, 0.8);
        }
        return c;
    }
    for w in 0..3 {
        let x0 = 0.03 + 0.45 * cell(seed, w, 0, 4);
        let y0 = 0.04 + 0.35 * cell(seed, w, 0, 5);
        let rect = [
            x0,
            y0,
            x0 + 0.35 + 0.2 * cell(seed, w, 0, 6),
            y0 + 0.35 + 0.2 * cell(seed, w, 0, 7),
        ];
        if !inside(u, v, rect) {
            continue;
        }
        let (bg, fg) = if dark {
            ([0.13, 0.14, 0.17], [0.85, 0.85, 0.8])
        } else {
            ([0.97, 0.97, 0.97], [0.15, 0.15, 0.2])
        };
        c = if v < rect[1] + 0.04 {
            [0.3, 0.33, 0.4]
        } else {
            bg
        };
        let (x, y) = (u - rect[0] - 0.015, v - rect[1] - 0.06);
        if text_ink(
            seed ^ w as u64,
            x,
            y,
            0.011,
            0.028,
            rect[2] - rect[0] - 0.03,
        ) {
            let token = cell(seed, (x / 0.06) as i64, (y / 0.028) as i64, 8);
            c = if token < 0.6 {
                fg
            } else {
                hsv(token * 3.0, 0.6, 0.85)
            };
        }
    }
    c
}

/// Marker drawings on a whiteboard: boxes with text, arrows, a plotted curve, ghosted smudges.
pub fn whiteboard(seed: u64, u: f32, v: f32) -> Rgb {
    let mut c = scale([0.95, 0.96, 0.96], 0.94 + 0.06 * fbm(seed, u, v, [6, 4], 3));
    let inks = [
        [0.1, 0.2, 0.6],
        [0.7, 0.1, 0.1],
        [0.1, 0.1, 0.1],
        [0.1, 0.45, 0.2],
    ];
    let mut centres = Vec::new();
    for b in 0..4 {
        let (x0, y0) = (0.05 + 0.25 * b as f32, 0.1 + 0.4 * cell(seed, b, 0, 1));
        let rect = [x0, y0, x0 + 0.17, y0 + 0.16];
        centres.push([x0 + 0.085, y0 + 0.08]);
        let ink = inks[b as usize % 4];
        let border = inside(
            u,
            v,
            [
                rect[0] - 0.005,
                rect[1] - 0.008,
                rect[2] + 0.005,
                rect[3] + 0.008,
            ],
        ) && !inside(u, v, rect);
        if border
            || (inside(u, v, rect)
                && text_ink(
                    seed ^ b as u64,
                    u - x0 - 0.015,
                    v - y0 - 0.02,
                    0.014,
                    0.04,
                    0.14,
                ))
        {
            c = ink;
        }
    }
    for pair in centres.windows(2) {
        if segment_distance(
            [u, v],
            [pair[0][0] + 0.09, pair[0][1]],
            [pair[1][0] - 0.09, pair[1][1]],
        ) < 0.004
        {
            c = inks[2];
        }
    }
    // A plot in the lower right.
    let (px, py) = ((u - 0.6) / 0.35, (0.95 - v) / 0.3);
    if (0.0..1.0).contains(&px) && (0.0..1.0).contains(&py) {
        let curve = 0.5 + 0.4 * (px * 7.0 + cell(seed, 0, 0, 2) * 6.0).sin() * (1.0 - px);
        if px < 0.01 || py < 0.015 || (py - curve).abs() < 0.02 {
            c = inks[1];
        }
    }
    if text_ink(seed ^ 77, u - 0.05, v - 0.7, 0.016, 0.045, 0.5) && v > 0.7 {
        c = inks[0];
    }
    c
}

/// Daylight outside over the light of the room, as a linear factor on the outside scene: three
/// stops, so the sky lands at 15 to 30 times an open wall (daylight through a window is 10 to 100
/// times an interior's luminance).
const DAYLIGHT_GAIN: f32 = 8.0;

/// The view out of a window as a camera metered for the room sees it: the sky, the clouds and the
/// sunlit façades clip to white, and only the darker glazing and the trees keep some texture, in
/// the top of the range.
pub fn window_view(seed: u64, u: f32, v: f32) -> Rgb {
    outside(seed, u, v).map(|c| {
        let light = unit_srgb_to_linear(c) * DAYLIGHT_GAIN;
        linear_to_srgb(light) as f32 / 255.0
    })
}

/// Sky, clouds, a row of buildings with lit windows, trees.
fn outside(seed: u64, u: f32, v: f32) -> Rgb {
    let skyline = 0.35 + 0.25 * cell(seed, (u * 7.0) as i64, 0, 1);
    let treeline = 0.72 + 0.12 * fbm(seed, u, 0.0, [9, 1], 3);
    if v > treeline {
        return scale(
            [0.2, 0.38, 0.16],
            0.6 + 0.6 * fbm(seed ^ 1, u, v, [24, 24], 3),
        );
    }
    if v > skyline {
        let b = (u * 7.0) as i64;
        let facade = hsv(
            0.08 + 0.1 * cell(seed, b, 0, 2),
            0.25,
            0.55 + 0.3 * cell(seed, b, 0, 3),
        );
        let window = (u * 56.0).fract() < 0.5 && (v * 40.0).fract() < 0.55;
        return if window {
            if cell(seed, (u * 56.0) as i64, (v * 40.0) as i64, 4) < 0.3 {
                [0.9, 0.85, 0.6]
            } else {
                [0.25, 0.3, 0.38]
            }
        } else {
            facade
        };
    }
    let sky = mix([0.45, 0.65, 0.92], [0.85, 0.9, 0.97], v / skyline);
    if fbm(seed ^ 2, u, v * 2.0, [5, 3], 4) > 0.55 {
        [0.97, 0.97, 0.97]
    } else {
        sky
    }
}

/// Keys on a dark deck (fit to the top face).
pub fn keyboard(seed: u64, u: f32, v: f32) -> Rgb {
    let (ku, kv) = (u * 15.0, v * 5.0);
    let row = kv.floor() as i64;
    let key = if row == 4 && (4.0..11.0).contains(&ku) {
        (ku - 4.0) / 7.0
    } else {
        ku.fract()
    };
    let in_key = (0.08..0.92).contains(&key) && (0.1..0.9).contains(&kv.fract());
    if !in_key {
        return [0.08, 0.08, 0.09];
    }
    let key_seed = seed ^ (ku as u64 + 16 * row as u64);
    let glyph = text_ink(
        key_seed,
        (ku.fract() - 0.3) * 0.05,
        (kv.fract() - 0.25) * 0.07,
        0.05,
        0.07,
        1.0,
    );
    if glyph && row < 4 {
        [0.85, 0.85, 0.85]
    } else {
        [0.22, 0.22, 0.24]
    }
}
