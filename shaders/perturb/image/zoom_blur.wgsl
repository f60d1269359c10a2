// zoom_blur: the mean of the image and its centre zooms (imagecorruptions `zoom_blur`): each zoom
// crops the centre ceil(H/z) x ceil(W/z) and scales it back up with SciPy's `zoom(order=1)`
// (bilinear, corner-aligned: source = top + out * (crop - 1) / (round(crop * z) - 1)).
#include "common/color.wgsl"
#include "perturb/image/filter.wgsl"

struct Zooms {
    // count is a multiple of 4; padded zooms have weight 0.
    count: i32,
    _pad0: i32,
    _pad1: i32,
    // 1 / (number of zooms + 1): the image itself counts once.
    inverse_total: f32,
    // (top x, top y, scale x, scale y) per zoom.
    windows: array<vec4<f32>, 16>,
    // weight (1 or 0) in .x
    weights: array<vec4<f32>, 16>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> zooms: Zooms;

fn zoomed(k: i32, p: vec2<f32>, last: vec2<i32>) -> vec3<f32> {
    let window = zooms.windows[k];
    let coordinate = window.xy + p * window.zw;
    let base = floor(coordinate);
    let f = coordinate - base;
    let q = vec2<i32>(base);
    let q1 = min(q + 1, last);
    let a = textureLoad(source, q, 0).rgb;
    let b = textureLoad(source, vec2<i32>(q1.x, q.y), 0).rgb;
    let c = textureLoad(source, vec2<i32>(q.x, q1.y), 0).rgb;
    let d = textureLoad(source, q1, 0).rgb;
    let upper = a * (1.0 - f.x) + b * f.x;
    let lower = c * (1.0 - f.x) + d * f.x;
    return zooms.weights[k].x * (upper * (1.0 - f.y) + lower * f.y);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    let last = size - 1;
    let pf = vec2<f32>(p);
    var sum = textureLoad(source, p, 0).rgb;
    for (var k = 0; k < zooms.count; k += 4) {
        sum += zoomed(k, pf, last) + zoomed(k + 1, pf, last);
        sum += zoomed(k + 2, pf, last) + zoomed(k + 3, pf, last);
    }
    textureStore(output, p, vec4<f32>(truncate8(sum * zooms.inverse_total + SUM_EPSILON), 1.0));
}
