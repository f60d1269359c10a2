// Three channels for filter_rows.wgsl into an f32 texture: the first half of gaussian_blur's and
// glass_blur's Gaussian, read from the frame's colour.

alias Value = vec3<f32>;

@group(0) @binding(1) var output: texture_storage_2d<rgba32float, write>;

fn value(t: vec4<f32>) -> Value {
    return t.rgb;
}

fn texel(v: Value) -> vec4<f32> {
    return vec4<f32>(v, 0.0);
}
