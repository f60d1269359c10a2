// brightness: V += delta in HSV (imagecorruptions `brightness`, skimage rgb2hsv/hsv2rgb).
#include "common/color.wgsl"
#include "perturb/image/pointwise_runs.wgsl"

struct Params {
    key: vec4<u32>,
    // x: delta V
    values: vec4<f32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Params;

fn corrupt(p: vec2<u32>, x: vec3<f32>) -> vec3<f32> {
    var hsv = rgb_to_hsv(x);
    hsv.z = clamp(hsv.z + params.values.x, 0.0, 1.0);
    return hsv_to_rgb(hsv);
}
