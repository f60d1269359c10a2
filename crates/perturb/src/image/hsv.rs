//! scikit-image's rgb2hsv / hsv2rgb, mirrored by `shaders/common/color.wgsl`.

/// RGB → HSV: V = max, S = delta / V, H in [0, 1); blue wins ties over green over red.
pub fn rgb_to_hsv([r, g, b]: [f32; 3]) -> [f32; 3] {
    let v = r.max(g).max(b);
    let delta = v - r.min(g).min(b);
    if delta == 0.0 {
        return [0.0, 0.0, v];
    }
    let h = if b == v {
        4.0 + (r - g) / delta
    } else if g == v {
        2.0 + (b - r) / delta
    } else {
        (g - b) / delta
    } / 6.0;
    [h - h.floor(), delta / v, v]
}

/// HSV → RGB, sector floor(6H) mod 6.
pub fn hsv_to_rgb([h, s, v]: [f32; 3]) -> [f32; 3] {
    let h6 = h * 6.0;
    let sector = h6.floor();
    let f = h6 - sector;
    let p = v * (1.0 - s);
    let q = v * (1.0 - f * s);
    let t = v * (1.0 - (1.0 - f) * s);
    match (sector as u32) % 6 {
        0 => [v, t, p],
        1 => [q, v, p],
        2 => [p, v, t],
        3 => [p, q, v],
        4 => [t, p, v],
        _ => [v, p, q],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOL: f32 = 1e-6;

    #[test]
    fn round_trip_and_known_values() {
        assert_eq!(rgb_to_hsv([1.0, 0.0, 0.0]), [0.0, 1.0, 1.0]);
        let [h, s, v] = rgb_to_hsv([0.0, 0.5, 1.0]);
        assert!((h - 7.0 / 12.0).abs() < TOL && s == 1.0 && v == 1.0);
        assert_eq!(rgb_to_hsv([0.3, 0.3, 0.3]), [0.0, 0.0, 0.3]);
        for rgb in [
            [0.2, 0.7, 0.4],
            [0.9, 0.1, 0.5],
            [0.5, 0.5, 0.1],
            [0.05, 0.0, 1.0],
        ] {
            let back = hsv_to_rgb(rgb_to_hsv(rgb));
            for c in 0..3 {
                assert!((back[c] - rgb[c]).abs() < TOL, "{rgb:?} -> {back:?}");
            }
        }
    }
}
