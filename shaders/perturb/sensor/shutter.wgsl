// The shutter of exposure and rolling_shutter: sub-frames rendered from the camera's poses
// during capture are summed in linear light, weighted, over the rows each one covers
// (`accumulate`, once per sub-frame), then encoded to sRGB into the frame (`resolve`).
#include "common/color.wgsl"

struct Params {
    // x: first row, y: row count, z: 1 = start the sum (overwrite), 0 = add to it
    rows: vec4<u32>,
    // x: weight of this sub-frame
    weight: vec4<f32>,
}

@group(0) @binding(0) var subframe: texture_2d<f32>;
@group(0) @binding(1) var<storage, read_write> sum: array<vec4<f32>>;
@group(0) @binding(2) var<uniform> params: Params;
@group(0) @binding(3) var output: texture_storage_2d<rgba8unorm, write>;

@compute @workgroup_size(8, 8)
fn accumulate(@builtin(global_invocation_id) id: vec3<u32>) {
    let width = textureDimensions(subframe).x;
    if (id.x >= width || id.y >= params.rows.y) {
        return;
    }
    let p = vec2<u32>(id.x, params.rows.x + id.y);
    let i = p.y * width + p.x;
    let light = srgb_to_linear(textureLoad(subframe, p, 0).rgb) * params.weight.x;
    if (params.rows.z == 1u) {
        sum[i] = vec4<f32>(light, 0.0);
    } else {
        sum[i] = sum[i] + vec4<f32>(light, 0.0);
    }
}

@compute @workgroup_size(8, 8)
fn resolve(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(output);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let light = sum[id.y * size.x + id.x].rgb;
    textureStore(output, id.xy, vec4<f32>(linear_to_srgb(light), 1.0));
}
