// glass_blur, one sweep: every pixel with δ < y <= H-δ and δ < x <= W-δ takes the value of a
// neighbour at a random offset in [-δ, δ-1] per axis (imagecorruptions swaps pixels in one
// sequential sweep; this parallel gather keeps the displacement statistics). Between the two
// Gaussian blurs (gaussian_blur_rows.wgsl, gaussian_blur.wgsl).
#include "common/rng.wgsl"

struct Sweep {
    key: vec4<u32>,
    delta: i32,
    iteration: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> sweep: Sweep;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    var q = p;
    let d = sweep.delta;
    if (all(p > vec2<i32>(d)) && all(p <= size - d)) {
        let bits = rng_draw(sweep.key, vec4<u32>(id.xy, sweep.iteration, 0u));
        let span = u32(2 * d);
        q = p + vec2<i32>(bits.xy % span) - d;
    }
    textureStore(output, p, textureLoad(source, q, 0));
}
