//! Textiles: woven upholstery, leather, office carpet tiles, curtains, patterned rugs.

use std::f32::consts::{PI, TAU};

use super::noise::{band, cell, fbm, grid_distance, hsv, mix, scale, value_noise, Rgb};

fn fabric_palette(seed: u64) -> [Rgb; 3] {
    let h = cell(seed, 0, 0, 10);
    let s = 0.1 + 0.3 * cell(seed, 0, 0, 11);
    [
        hsv(h, s, 0.62),
        hsv(h + 0.04, s * 0.8, 0.52),
        hsv(h + 0.5, s * 0.5, 0.7),
    ]
}

/// Plain weave (over/under threads); most upholstery is plain, some tartan, stripes or dots.
pub fn fabric(seed: u64, u: f32, v: f32) -> Rgb {
    const THREADS: f32 = 128.0;
    let [a, b, accent] = fabric_palette(seed);
    let (tu, tv) = (u * THREADS, v * THREADS);
    let over = ((tu.floor() + tv.floor()) as i64).rem_euclid(2) == 0;
    let along = if over { tu.fract() } else { tv.fract() };
    let thread = 0.88 + 0.12 * (along * PI).sin();
    let design = (cell(seed, 0, 0, 12) * 8.0).max(4.0) as u32 - 4;
    let base = match design {
        0 => mix(a, b, fbm(seed, u, v, [8, 8], 3)),
        1 => {
            let s = band((u * 4.0).fract(), 0.5, 0.12) + band((v * 4.0).fract(), 0.5, 0.12);
            let line = band((u * 4.0).fract(), 0.2, 0.02).max(band((v * 4.0).fract(), 0.2, 0.02));
            mix(mix(a, b, s * 0.5), accent, line)
        }
        2 => mix(
            a,
            if (v * 12.0 + 0.5).fract() < 0.35 {
                b
            } else {
                accent
            },
            0.6,
        ),
        _ => {
            let (cu, cv) = ((u * 10.0).fract() - 0.5, (v * 10.0).fract() - 0.5);
            mix(a, accent, if cu * cu + cv * cv < 0.06 { 0.8 } else { 0.0 })
        }
    };
    scale(
        base,
        thread * (0.9 + 0.1 * fbm(seed ^ 1, u, v, [32, 32], 2)),
    )
}

/// Dyed leather: an even colour with a faint pebble grain (±7 % of the albedo from one 5 mm cell to
/// the next), a soft patina and the odd crease. A grain of ±37 % covered office1's chairs and
/// office3's sofa with strong corners no real leather has, and office1 shrugged off fog and
/// contrast (validity.md, "Leather that looks like leather").
pub fn leather(seed: u64, u: f32, v: f32) -> Rgb {
    let base = [[0.42, 0.25, 0.16], [0.24, 0.22, 0.21], [0.62, 0.41, 0.23]]
        [(cell(seed, 0, 0, 20) * 3.0) as usize];
    let pebbles = value_noise(seed, u * 96.0, v * 96.0, [96, 96]);
    let patina = fbm(seed ^ 3, u, v, [4, 4], 3);
    let creases = (1.0 - (fbm(seed ^ 7, u, v, [6, 6], 4) - 0.5).abs() * 14.0).max(0.0);
    scale(base, 0.8 + 0.15 * pebbles + 0.3 * patina - 0.25 * creases)
}

/// Half-metre carpet tiles (two per texture side) laid in alternating pile direction.
pub fn office_carpet(seed: u64, u: f32, v: f32) -> Rgb {
    let base = mix(
        [0.32, 0.35, 0.4],
        hsv(cell(seed, 0, 0, 30), 0.15, 0.45),
        0.5,
    );
    let (iu, iv) = ((u * 2.0).floor() as i64, (v * 2.0).floor() as i64);
    let turned = (iu + iv).rem_euclid(2) == 1;
    let (a, b) = if turned { (v, u) } else { (u, v) };
    let rib = ((a * 96.0 * TAU).sin() * 0.5 + 0.5) * 0.25;
    let pile = fbm(seed, u, v, [128, 128], 2);
    let fleck = if cell(seed, (u * 256.0) as i64, (v * 256.0) as i64, 31) > 0.93 {
        0.3
    } else {
        0.0
    };
    let seam = if grid_distance(u * 2.0) < 0.004 || grid_distance(v * 2.0) < 0.004 {
        0.6
    } else {
        1.0
    };
    let mottle = fbm(seed ^ 3, b, a, [4, 4], 3);
    scale(
        base,
        seam * (0.85 + 0.2 * pile + 0.4 * rib + 0.4 * fleck) * (0.9 + 0.15 * mottle),
    )
}

/// Vertical folds with a woven texture.
pub fn curtain(seed: u64, u: f32, v: f32) -> Rgb {
    let fold = (u * 8.0 * TAU + 0.8 * fbm(seed, u, v, [4, 2], 2)).sin() * 0.5 + 0.5;
    scale(fabric(seed, u, v), 0.8 + 0.25 * fold)
}

/// A rug fitted to its quad: fringe, borders, a medallion and a field of small diamonds.
pub fn rug(seed: u64, u: f32, v: f32) -> Rgb {
    let h = cell(seed, 0, 0, 40);
    let field = hsv(h, 0.6, 0.55);
    let border = hsv(h + 0.55, 0.5, 0.35);
    let cream = [0.9, 0.85, 0.72];
    let (x, y) = (u * 2.0 - 1.0, v * 2.0 - 1.0);
    let edge = (1.0 - x.abs()).min(1.0 - y.abs());
    let wool = 0.85 + 0.25 * fbm(seed, u, v, [96, 96], 2);
    let c = if (1.0 - x.abs()) < 0.03 {
        // Fringe.
        if ((v * 120.0).fract()) < 0.5 {
            cream
        } else {
            scale(cream, 0.7)
        }
    } else if edge < 0.1 {
        let stripe = ((edge * 60.0).floor() as i64).rem_euclid(3);
        [border, cream, scale(field, 0.7)][stripe as usize]
    } else {
        let d = x.abs() + y.abs() * 1.6;
        if d < 0.5 {
            let ring = ((d * 14.0).floor() as i64).rem_euclid(3);
            [cream, border, hsv(h + 0.1, 0.7, 0.7)][ring as usize]
        } else {
            let (cu, cv) = ((u * 14.0).fract() - 0.5, (v * 10.0).fract() - 0.5);
            if cu.abs() + cv.abs() < 0.22 {
                cream
            } else {
                field
            }
        }
    };
    scale(c, wool)
}
