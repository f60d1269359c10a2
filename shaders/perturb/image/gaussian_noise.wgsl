// gaussian_noise: x + N(0, sigma) per pixel and channel (imagecorruptions `gaussian_noise`).
#include "common/rng.wgsl"
#include "common/color.wgsl"

struct Params {
    key: vec4<u32>,
    // x: sigma
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
    let x = textureLoad(source, id.xy, 0).rgb;
    let noise = rng_normal3(params.key, vec4<u32>(id.x, id.y, 0u, 0u));
    textureStore(output, id.xy, vec4<f32>(truncate8(x + params.values.x * noise), 1.0));
}
