// contrast, pass 2: (x - mean) * c + mean with the per-channel means of the frame
// (imagecorruptions `contrast`).
#include "common/color.wgsl"
#include "perturb/image/pointwise_runs.wgsl"

struct Params {
    key: vec4<u32>,
    // x: factor c
    values: vec4<f32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Params;
// (sum r, sum g, sum b, pixel count) from contrast_mean.wgsl
@group(0) @binding(3) var<uniform> sums: vec4<f32>;

fn corrupt(p: vec2<u32>, x: vec3<f32>) -> vec3<f32> {
    let mean = sums.rgb / sums.w;
    return (x - mean) * params.values.x + mean;
}
