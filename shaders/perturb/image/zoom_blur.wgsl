// zoom_blur: the mean of the image and its centre zooms (imagecorruptions `zoom_blur`): each zoom
// crops the centre ceil(H/z) x ceil(W/z) and scales it back up with SciPy's `zoom(order=1)`
// (bilinear, corner-aligned: source = top + out * (crop - 1) / (round(crop * z) - 1)). Each
// invocation writes a run of 8 pixels of a row (one zoom read per 8 outputs; see filter.wgsl).
#include "common/color.wgsl"
#include "perturb/image/filter.wgsl"

struct Zooms {
    count: i32,
    _pad0: i32,
    _pad1: i32,
    // 1 / (number of zooms + 1): the image itself counts once.
    inverse_total: f32,
    // (top x, top y, scale x, scale y) per zoom.
    windows: array<vec4<f32>, 16>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> zooms: Zooms;

// Bilinear read at (x, y); the right and lower neighbours are clamped to the image.
fn bilinear(x: f32, y: i32, fy: f32, y1: i32, last_x: i32) -> vec3<f32> {
    let bx = floor(x);
    let fx = x - bx;
    let q = i32(bx);
    let q1 = min(q + 1, last_x);
    let upper = textureLoad(source, vec2<i32>(q, y), 0).rgb * (1.0 - fx)
        + textureLoad(source, vec2<i32>(q1, y), 0).rgb * fx;
    let lower = textureLoad(source, vec2<i32>(q, y1), 0).rgb * (1.0 - fx)
        + textureLoad(source, vec2<i32>(q1, y1), 0).rgb * fx;
    return upper * (1.0 - fy) + lower * fy;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let x0 = i32(id.x) * 8;
    let y = i32(id.y);
    if (x0 >= size.x || y >= size.y) {
        return;
    }
    let last = size - 1;
    var s0 = textureLoad(source, vec2<i32>(min(x0 + 0, last.x), y), 0).rgb;
    var s1 = textureLoad(source, vec2<i32>(min(x0 + 1, last.x), y), 0).rgb;
    var s2 = textureLoad(source, vec2<i32>(min(x0 + 2, last.x), y), 0).rgb;
    var s3 = textureLoad(source, vec2<i32>(min(x0 + 3, last.x), y), 0).rgb;
    var s4 = textureLoad(source, vec2<i32>(min(x0 + 4, last.x), y), 0).rgb;
    var s5 = textureLoad(source, vec2<i32>(min(x0 + 5, last.x), y), 0).rgb;
    var s6 = textureLoad(source, vec2<i32>(min(x0 + 6, last.x), y), 0).rgb;
    var s7 = textureLoad(source, vec2<i32>(min(x0 + 7, last.x), y), 0).rgb;
    for (var k = 0; k < zooms.count; k++) {
        let w = zooms.windows[k];
        let cy = w.y + f32(y) * w.w;
        let by = floor(cy);
        let fy = cy - by;
        let row = i32(by);
        let row1 = min(row + 1, last.y);
        s0 += bilinear(w.x + f32(x0 + 0) * w.z, row, fy, row1, last.x);
        s1 += bilinear(w.x + f32(x0 + 1) * w.z, row, fy, row1, last.x);
        s2 += bilinear(w.x + f32(x0 + 2) * w.z, row, fy, row1, last.x);
        s3 += bilinear(w.x + f32(x0 + 3) * w.z, row, fy, row1, last.x);
        s4 += bilinear(w.x + f32(x0 + 4) * w.z, row, fy, row1, last.x);
        s5 += bilinear(w.x + f32(x0 + 5) * w.z, row, fy, row1, last.x);
        s6 += bilinear(w.x + f32(x0 + 6) * w.z, row, fy, row1, last.x);
        s7 += bilinear(w.x + f32(x0 + 7) * w.z, row, fy, row1, last.x);
    }
    if (x0 + 0 < size.x) {
        let value = truncate8(s0 * zooms.inverse_total + SUM_EPSILON);
        textureStore(output, vec2<i32>(x0 + 0, y), vec4<f32>(value, 1.0));
    }
    if (x0 + 1 < size.x) {
        let value = truncate8(s1 * zooms.inverse_total + SUM_EPSILON);
        textureStore(output, vec2<i32>(x0 + 1, y), vec4<f32>(value, 1.0));
    }
    if (x0 + 2 < size.x) {
        let value = truncate8(s2 * zooms.inverse_total + SUM_EPSILON);
        textureStore(output, vec2<i32>(x0 + 2, y), vec4<f32>(value, 1.0));
    }
    if (x0 + 3 < size.x) {
        let value = truncate8(s3 * zooms.inverse_total + SUM_EPSILON);
        textureStore(output, vec2<i32>(x0 + 3, y), vec4<f32>(value, 1.0));
    }
    if (x0 + 4 < size.x) {
        let value = truncate8(s4 * zooms.inverse_total + SUM_EPSILON);
        textureStore(output, vec2<i32>(x0 + 4, y), vec4<f32>(value, 1.0));
    }
    if (x0 + 5 < size.x) {
        let value = truncate8(s5 * zooms.inverse_total + SUM_EPSILON);
        textureStore(output, vec2<i32>(x0 + 5, y), vec4<f32>(value, 1.0));
    }
    if (x0 + 6 < size.x) {
        let value = truncate8(s6 * zooms.inverse_total + SUM_EPSILON);
        textureStore(output, vec2<i32>(x0 + 6, y), vec4<f32>(value, 1.0));
    }
    if (x0 + 7 < size.x) {
        let value = truncate8(s7 * zooms.inverse_total + SUM_EPSILON);
        textureStore(output, vec2<i32>(x0 + 7, y), vec4<f32>(value, 1.0));
    }
}
