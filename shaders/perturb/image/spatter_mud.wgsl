// spatter (mud), final pass: the blurred mud mask (filter_rows / filter_columns of the mask)
// zeroed below 0.8, pasting mud brown: x (1 - m) + m (63, 42, 20) / 255 (imagecorruptions
// `spatter`, severities 4-5).
#include "common/color.wgsl"
#include "perturb/image/pointwise_runs.wgsl"

struct Mud {
    color: vec4<f32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> mud: Mud;
@group(0) @binding(3) var mask: texture_2d<f32>;

fn corrupt(p: vec2<u32>, x: vec3<f32>) -> vec3<f32> {
    var m = textureLoad(mask, p, 0).x;
    if (m < 0.8) {
        m = 0.0;
    }
    return x * (1.0 - m) + m * mud.color.rgb;
}
