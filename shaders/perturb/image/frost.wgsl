// frost, per frame: a * x + b * F with the frost texture F cropped at the frame's offset
// (imagecorruptions `frost` blends a randomly cropped frost photo the same way).
#include "common/color.wgsl"
#include "perturb/image/pointwise_runs.wgsl"

struct Frost {
    offset: vec2<i32>,
    image_weight: f32,
    frost_weight: f32,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> frost: Frost;
@group(0) @binding(3) var ice: texture_2d<f32>;

fn corrupt(p: vec2<u32>, x: vec3<f32>) -> vec3<f32> {
    let f = textureLoad(ice, vec2<i32>(p) + frost.offset, 0).rgb;
    return frost.image_weight * x + frost.frost_weight * f;
}
