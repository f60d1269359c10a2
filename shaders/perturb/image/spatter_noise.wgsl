// spatter, pass 1: the liquid layer's Gaussian noise N(mean, std), one draw per pixel; passes 2-3
// (filter_rows, filter_columns) blur it.
#include "common/rng.wgsl"

struct Noise {
    key: vec4<u32>,
    mean: f32,
    deviation: f32,
    _pad0: f32,
    _pad1: f32,
}

@group(0) @binding(0) var output: texture_storage_2d<r32float, write>;
@group(0) @binding(1) var<uniform> noise: Noise;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(output);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let bits = rng_draw(noise.key, vec4<u32>(id.xy, 0u, 0u));
    let value = noise.mean + noise.deviation * rng_normal_pair(bits.x, bits.y).x;
    textureStore(output, id.xy, vec4<f32>(value, 0.0, 0.0, 0.0));
}
