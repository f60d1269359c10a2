// spatter (water), final pass: x + intensity * m / max(m) * pale turquoise (175, 238, 238) / 255
// (imagecorruptions `spatter`, severities 1-3).
#include "common/color.wgsl"

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

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(source);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let top = bitcast<f32>(maximum[0]);
    var m = 0.0;
    if (top > 0.0) {
        m = textureLoad(shade, id.xy, 0).x / top * water.intensity;
    }
    let x = textureLoad(source, id.xy, 0).rgb;
    textureStore(output, id.xy, vec4<f32>(truncate8(x + m * water.color.rgb), 1.0));
}
