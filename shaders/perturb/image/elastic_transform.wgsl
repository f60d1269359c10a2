// elastic_transform, final pass: resample the image at (x, y) + α·(smoothed fields), bilinearly
// with reflected edges (SciPy map_coordinates(order=1, mode='reflect')).
#include "common/color.wgsl"
#include "perturb/image/pointwise_runs.wgsl"

struct Warp {
    alpha: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> warp: Warp;
@group(0) @binding(3) var fields: texture_2d<f32>;

fn reflect(i: i32, n: i32) -> i32 {
    if (i < 0) {
        return -1 - i;
    }
    if (i >= n) {
        return 2 * n - 1 - i;
    }
    return i;
}

fn pixel(x: i32, y: i32, size: vec2<i32>) -> vec3<f32> {
    return textureLoad(source, vec2<i32>(reflect(x, size.x), reflect(y, size.y)), 0).rgb;
}

// `x`, the pixel itself, is not used: the warp reads around the displaced point.
fn corrupt(p: vec2<u32>, x: vec3<f32>) -> vec3<f32> {
    let size = vec2<i32>(textureDimensions(source));
    let at = vec2<f32>(p) + warp.alpha * textureLoad(fields, p, 0).xy;
    let base = floor(at);
    let f = at - base;
    let q = vec2<i32>(base);
    let upper = mix(pixel(q.x, q.y, size), pixel(q.x + 1, q.y, size), f.x);
    let lower = mix(pixel(q.x, q.y + 1, size), pixel(q.x + 1, q.y + 1, size), f.x);
    return mix(upper, lower, f.y);
}
