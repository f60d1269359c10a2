// saturate: S' = clip(S·m + o, 0, 1) in HSV (imagecorruptions `saturate`).
#include "common/color.wgsl"

struct Params {
    key: vec4<u32>,
    // x: S multiplier m, y: S offset o
    values: vec4<f32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Params;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(source);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    var hsv = rgb_to_hsv(textureLoad(source, id.xy, 0).rgb);
    hsv.y = clamp(hsv.y * params.values.x + params.values.y, 0.0, 1.0);
    textureStore(output, id.xy, vec4<f32>(truncate8(hsv_to_rgb(hsv)), 1.0));
}
