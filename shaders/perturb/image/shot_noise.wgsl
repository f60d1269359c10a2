// shot_noise: Poisson(x·c) / c per pixel and channel, c photons at full scale (imagecorruptions
// `shot_noise`). The Poisson sampler is exact at every rate (see common/rng.wgsl).
#include "common/rng.wgsl"
#include "common/color.wgsl"
#include "perturb/image/pointwise_runs.wgsl"

struct Params {
    key: vec4<u32>,
    // x: photons c
    values: vec4<f32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Params;

fn corrupt(p: vec2<u32>, x: vec3<f32>) -> vec3<f32> {
    let c = params.values.x;
    var y: vec3<f32>;
    for (var channel = 0u; channel < 3u; channel++) {
        y[channel] = rng_poisson(params.key, vec3<u32>(p, channel), x[channel] * c) / c;
    }
    return y;
}
