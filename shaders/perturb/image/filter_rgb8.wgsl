// Three channels for filter_columns.wgsl into the frame's colour, truncated to 8 bits: the second
// half of gaussian_blur's and glass_blur's Gaussian.
#include "common/color.wgsl"

alias Value = vec3<f32>;

@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;

fn value(t: vec4<f32>) -> Value {
    return t.rgb;
}

fn texel(v: Value) -> vec4<f32> {
    return vec4<f32>(truncate8(v + SUM_EPSILON), 1.0);
}
