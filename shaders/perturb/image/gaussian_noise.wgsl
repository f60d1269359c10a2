// gaussian_noise: x + N(0, sigma) per pixel and channel (imagecorruptions `gaussian_noise`).
#include "common/rng.wgsl"
#include "common/color.wgsl"
#include "perturb/image/pointwise_runs.wgsl"

struct Params {
    key: vec4<u32>,
    // x: sigma
    values: vec4<f32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Params;

fn corrupt(p: vec2<u32>, x: vec3<f32>) -> vec3<f32> {
    return x + params.values.x * rng_normal3(params.key, vec4<u32>(p, 0u, 0u));
}
