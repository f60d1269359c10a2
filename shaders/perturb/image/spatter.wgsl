// spatter (water), final pass: x + intensity * m / max(m) * pale turquoise (175, 238, 238) / 255
// (imagecorruptions `spatter`, severities 1-3).
#include "common/color.wgsl"
#include "perturb/image/pointwise_runs.wgsl"

struct Water {
    color: vec4<f32>,
    intensity: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> water: Water;
@group(0) @binding(3) var shade: texture_2d<f32>;
@group(0) @binding(4) var<uniform> maximum: vec4<u32>;

fn corrupt(p: vec2<u32>, x: vec3<f32>) -> vec3<f32> {
    let top = bitcast<f32>(maximum[0]);
    var m = 0.0;
    if (top > 0.0) {
        m = textureLoad(shade, p, 0).x / top * water.intensity;
    }
    return x + m * water.color.rgb;
}
