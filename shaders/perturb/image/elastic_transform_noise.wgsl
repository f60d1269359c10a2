// elastic_transform, pass 1: uniform noise in [-max, max] (max = 0.005·H) for the x and y
// displacement fields, one draw per pixel. filter_rows / filter_columns smooth it next.
#include "common/rng.wgsl"

struct Noise {
    key: vec4<u32>,
    amplitude: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

@group(0) @binding(0) var fields: texture_storage_2d<rg32float, write>;
@group(0) @binding(1) var<uniform> noise: Noise;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(fields);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let bits = rng_draw(noise.key, vec4<u32>(id.xy, 0u, 0u));
    let u = vec2<f32>(rng_uniform(bits.x), rng_uniform(bits.y));
    textureStore(fields, id.xy, vec4<f32>((2.0 * u - 1.0) * noise.amplitude, 0.0, 0.0));
}
