//! What people's tops are woven or printed with, besides plain cloth: stripes (Breton, rugby,
//! pinstripes), checks (gingham, plaid) and printed T-shirts, each in one of the two-colour
//! pairs everyday clothes come in. Mapped in metres like the other textiles (a texture is half a
//! metre of cloth: u round the body, v along it), so every pattern repeats a whole number of
//! times across it.

use super::noise::{band, cell, fbm, mix, scale, Rgb};

/// Ground and figure colours (sRGB) of patterned everyday clothes.
const PAIRS: [(Rgb, Rgb); 8] = [
    ([0.12, 0.15, 0.3], [0.92, 0.92, 0.9]),
    ([0.92, 0.92, 0.9], [0.12, 0.15, 0.3]),
    ([0.62, 0.14, 0.14], [0.9, 0.88, 0.84]),
    ([0.1, 0.1, 0.1], [0.55, 0.55, 0.55]),
    ([0.55, 0.56, 0.58], [0.95, 0.95, 0.95]),
    ([0.25, 0.38, 0.28], [0.85, 0.82, 0.7]),
    ([0.3, 0.45, 0.7], [0.93, 0.94, 0.97]),
    ([0.75, 0.6, 0.35], [0.25, 0.2, 0.15]),
];

fn pair(seed: u64) -> (Rgb, Rgb) {
    PAIRS[(cell(seed, 0, 0, 40) * PAIRS.len() as f32) as usize]
}

/// A pick of `choices` by the seed's `slot`.
fn pick(seed: u64, slot: i64, choices: &[f32]) -> f32 {
    choices[(cell(seed, 0, 0, slot) * choices.len() as f32) as usize]
}

/// The cloth's weave over a colour: a few per cent of shading, as on the plain fabrics.
fn woven(seed: u64, u: f32, v: f32, colour: Rgb) -> Rgb {
    scale(colour, 0.94 + 0.06 * fbm(seed ^ 5, u, v, [32, 32], 2))
}

/// Stripes across the body, 8 to 25 to the half metre (2–6 cm apart), a quarter to a half of
/// each the figure colour.
pub fn stripes(seed: u64, u: f32, v: f32) -> Rgb {
    let (ground, figure) = pair(seed);
    let count = pick(seed, 41, &[8.0, 12.0, 16.0, 25.0]);
    let share = 0.25 + 0.25 * cell(seed, 0, 0, 42);
    // Centred in each repeat, so no edge falls on the texture's own.
    let stripe = band((v * count).fract(), 0.5, share / 2.0);
    woven(seed, u, v, mix(ground, figure, stripe))
}

/// Checks: bands of the figure colour both ways, half as strong where only one crosses
/// (gingham), 8 to 25 to the half metre; the widest (plaid) with a thin line of the ground
/// between bands.
pub fn checks(seed: u64, u: f32, v: f32) -> Rgb {
    let (ground, figure) = pair(seed);
    let count = pick(seed, 43, &[8.0, 12.0, 25.0]);
    let across = band((u * count).fract(), 0.5, 0.25);
    let along = band((v * count).fract(), 0.5, 0.25);
    let line = if count < 10.0 {
        band((u * count).fract(), 0.125, 0.03).max(band((v * count).fract(), 0.125, 0.03))
    } else {
        0.0
    };
    let colour = mix(ground, figure, 0.5 * (across + along));
    woven(seed, u, v, mix(colour, ground, line))
}

/// A printed T-shirt: plain ground with a print, a block of lettering over a round emblem in the
/// figure colour, repeating every half metre round the body (and on the sleeves): the body's
/// girth decides whether it falls on the chest, the back or the sides.
pub fn print(seed: u64, u: f32, v: f32) -> Rgb {
    let (ground, figure) = pair(seed);
    // The print fills u 0.1–0.4 and v 0.2–0.45 of the half metre: 15 × 12 cm.
    let (pu, pv) = ((u - 0.1) / 0.3, (v - 0.2) / 0.25);
    let inside = (0.0..1.0).contains(&pu) && (0.0..1.0).contains(&pv);
    let ink = if !inside {
        0.0
    } else if pv < 0.35 {
        // Three rows of letters, eight to a row: each letter a block of ink with gaps.
        let (col, row) = ((pu * 8.0).floor() as i64, (pv / 0.35 * 3.0).floor() as i64);
        let (fu, fv) = ((pu * 8.0).fract(), (pv / 0.35 * 3.0).fract());
        let stroke = cell(seed, col, row, 44) > 0.35 && fu < 0.75 && fv < 0.7;
        let hole =
            band(fu, 0.37, 0.12) * band(fv, 0.35, 0.12) > 0.0 && cell(seed, col, row, 45) > 0.5;
        if stroke && !hole {
            1.0
        } else {
            0.0
        }
    } else {
        // A ring round a disc, 7 cm across, in metres on the cloth.
        let (du, dv) = ((pu - 0.5) * 0.15, (pv - 0.68) * 0.125);
        let r = (du * du + dv * dv).sqrt();
        if r < 0.035 && !(0.022..0.027).contains(&r) {
            1.0
        } else {
            0.0
        }
    };
    woven(seed, u, v, mix(ground, figure, ink))
}
