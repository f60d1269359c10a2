// impulse_noise: each value (pixel and channel) becomes 0 or 1 with probability `amount`, with
// equal odds (imagecorruptions `impulse_noise` = skimage random_noise 's&p', salt_vs_pepper 0.5).
#include "common/rng.wgsl"
#include "common/color.wgsl"
#include "perturb/image/pointwise_runs.wgsl"

struct Params {
    key: vec4<u32>,
    // x: amount
    values: vec4<f32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Params;

fn impulse(x: f32, bits: u32, amount: f32) -> f32 {
    let u = rng_uniform(bits);
    if (u < 0.5 * amount) {
        return 1.0;
    }
    if (u < amount) {
        return 0.0;
    }
    return x;
}

fn corrupt(p: vec2<u32>, x: vec3<f32>) -> vec3<f32> {
    let u = rng_draw(params.key, vec4<u32>(p, 0u, 0u));
    let amount = params.values.x;
    return vec3<f32>(impulse(x.r, u.x, amount), impulse(x.g, u.y, amount), impulse(x.b, u.z, amount));
}
