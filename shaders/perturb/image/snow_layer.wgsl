// snow, pass 1 of 2: imagecorruptions' snow layer before its motion blur: Gaussian noise
// N(mean, std) on the H x W grid, `clipped_zoom`ed (centre crop scaled up by SciPy zoom(order=1),
// corner-aligned), values below the threshold set to 0, clipped to [0, 1]. Written for the whole
// zoomed size round(crop * z), which is at least H x W (the blur sees its edges).
#include "common/rng.wgsl"

struct Layer {
    key: vec4<u32>,
    // (top x, top y, scale x, scale y) of the zoom
    window: vec4<f32>,
    // zoomed layer size, noise grid size
    zoomed: vec2<u32>,
    grid: vec2<u32>,
    mean: f32,
    deviation: f32,
    threshold: f32,
    _pad: f32,
}

@group(0) @binding(0) var layer: texture_storage_2d<r32float, write>;
@group(0) @binding(1) var<uniform> params: Layer;

fn noise(p: vec2<i32>) -> f32 {
    let q = vec2<u32>(clamp(p, vec2<i32>(0), vec2<i32>(params.grid) - 1));
    let bits = rng_draw(params.key, vec4<u32>(q, 0u, 0u));
    return params.mean + params.deviation * rng_normal_pair(bits.x, bits.y).x;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.zoomed.x || id.y >= params.zoomed.y) {
        return;
    }
    let at = params.window.xy + vec2<f32>(id.xy) * params.window.zw;
    let base = floor(at);
    let f = at - base;
    let q = vec2<i32>(base);
    let upper = mix(noise(q), noise(q + vec2<i32>(1, 0)), f.x);
    let lower = mix(noise(q + vec2<i32>(0, 1)), noise(q + vec2<i32>(1, 1)), f.x);
    var v = mix(upper, lower, f.y);
    if (v < params.threshold) {
        v = 0.0;
    }
    textureStore(layer, id.xy, vec4<f32>(clamp(v, 0.0, 1.0), 0.0, 0.0, 0.0));
}
