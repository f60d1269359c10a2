// Colour helpers shared by the image corruptions, mirrored by crates/perturb/src/image_f32.rs
// and crates/perturb/src/image/hsv.rs.

// imagecorruptions quantises with np.uint8(clip(x, 0, 1) * 255), i.e. by truncation. Writing
// floor(v * 255) / 255 makes the Rgba8Unorm store (which rounds) reproduce that exactly.
fn truncate8(v: vec3<f32>) -> vec3<f32> {
    return floor(clamp(v, vec3<f32>(0.0), vec3<f32>(1.0)) * 255.0) / 255.0;
}

// RGB -> HSV as scikit-image's rgb2hsv: V = max, S = delta / V, H in [0, 1); blue wins ties over
// green over red; H = S = 0 where delta = 0.
fn rgb_to_hsv(c: vec3<f32>) -> vec3<f32> {
    let v = max(c.r, max(c.g, c.b));
    let delta = v - min(c.r, min(c.g, c.b));
    if (delta == 0.0) {
        return vec3<f32>(0.0, 0.0, v);
    }
    let s = delta / v;
    var h: f32;
    if (c.b == v) {
        h = 4.0 + (c.r - c.g) / delta;
    } else if (c.g == v) {
        h = 2.0 + (c.b - c.r) / delta;
    } else {
        h = (c.g - c.b) / delta;
    }
    h = h / 6.0;
    h = h - floor(h);
    return vec3<f32>(h, s, v);
}

// HSV -> RGB as scikit-image's hsv2rgb (sector floor(6H) mod 6).
fn hsv_to_rgb(hsv: vec3<f32>) -> vec3<f32> {
    let h6 = hsv.x * 6.0;
    let sector = floor(h6);
    let f = h6 - sector;
    let s = hsv.y;
    let v = hsv.z;
    let p = v * (1.0 - s);
    let q = v * (1.0 - f * s);
    let t = v * (1.0 - (1.0 - f) * s);
    switch (u32(sector) % 6u) {
        case 0u: { return vec3<f32>(v, t, p); }
        case 1u: { return vec3<f32>(q, v, p); }
        case 2u: { return vec3<f32>(p, v, t); }
        case 3u: { return vec3<f32>(p, q, v); }
        case 4u: { return vec3<f32>(t, p, v); }
        default: { return vec3<f32>(v, p, q); }
    }
}

// sRGB transfer function (IEC 61966-2-1), mirrored by image_f32.rs `srgb_to_linear` /
// `linear_to_srgb`: averaging light (exposure, vignetting) happens on linear values.
fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    let low = c / 12.92;
    let high = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(high, low, c <= vec3<f32>(0.04045));
}

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let x = clamp(c, vec3<f32>(0.0), vec3<f32>(1.0));
    let low = x * 12.92;
    let high = 1.055 * pow(x, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(high, low, x <= vec3<f32>(0.0031308));
}
