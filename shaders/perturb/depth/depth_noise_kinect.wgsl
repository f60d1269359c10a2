// depth_noise_kinect: axial noise of a structured-light sensor, z + N(0, k·σ(z)) with
// σ(z) = 0.0012 + 0.0019·(z − 0.4)² metres (Nguyen, Izadi & Lovell 2012, Kinect v1), clamped at
// 0; invalid stays invalid.
#include "common/rng.wgsl"

struct Params {
    key: vec4<u32>,
    // x: multiplier k of the sensor's sigma
    values: vec4<f32>,
}

@group(0) @binding(0) var depth: texture_storage_2d<r32float, read_write>;
@group(0) @binding(1) var<uniform> params: Params;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(depth);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let z = textureLoad(depth, id.xy).x;
    if (z <= 0.0) {
        return;
    }
    let sigma = 0.0012 + 0.0019 * (z - 0.4) * (z - 0.4);
    let u = rng_draw(params.key, vec4<u32>(id.x, id.y, 0u, 0u));
    let n = rng_normal_pair(u.x, u.y).x;
    textureStore(depth, id.xy, vec4<f32>(max(z + params.values.x * sigma * n, 0.0)));
}
