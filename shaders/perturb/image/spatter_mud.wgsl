// spatter (mud), final pass: the blurred mud mask (filter_rows / filter_columns of the mask)
// zeroed below 0.8, pasting mud brown: x (1 - m) + m (63, 42, 20) / 255 (imagecorruptions
// `spatter`, severities 4-5).
#include "common/color.wgsl"

struct Mud {
    color: vec4<f32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> mud: Mud;
@group(0) @binding(3) var mask: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(source);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    var m = textureLoad(mask, id.xy, 0).x;
    if (m < 0.8) {
        m = 0.0;
    }
    let x = textureLoad(source, id.xy, 0).rgb;
    textureStore(output, id.xy, vec4<f32>(truncate8(x * (1.0 - m) + m * mud.color.rgb), 1.0));
}
