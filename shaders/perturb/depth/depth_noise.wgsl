// depth_noise, pass 2: z + N(0, c·std(valid z)), clamped at 0; invalid stays invalid.
#include "common/rng.wgsl"

struct Params {
    key: vec4<u32>,
    // x: c
    values: vec4<f32>,
}

@group(0) @binding(0) var depth: texture_storage_2d<r32float, read_write>;
@group(0) @binding(1) var<uniform> params: Params;
// (sum z, sum z², valid count, 0) from depth_noise_stats.wgsl
@group(0) @binding(2) var<uniform> sums: vec4<f32>;

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
    let mean = sums.x / sums.z;
    let deviation = sqrt(max(sums.y / sums.z - mean * mean, 0.0));
    let u = rng_draw(params.key, vec4<u32>(id.x, id.y, 0u, 0u));
    let n = rng_normal_pair(u.x, u.y).x;
    textureStore(depth, id.xy, vec4<f32>(max(z + params.values.x * deviation * n, 0.0)));
}
