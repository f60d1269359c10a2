// spatter (water), pass 5: OpenCV Canny's gradient on the 8-bit liquid layer: Sobel 3x3 (edges
// replicated), gx and gy (integers within +-1020) packed as two 16-bit halves for the non-maximum
// suppression of pass 6, a quarter of the bytes of three floats.
#include "perturb/image/window_runs.wgsl"
#include "perturb/image/spatter_layer.wgsl"

@group(0) @binding(0) var blurred: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<r32uint, write>;
@group(0) @binding(2) var<uniform> liquid: Liquid;

fn frame_size() -> vec2<i32> {
    return vec2<i32>(textureDimensions(blurred));
}

fn sample(p: vec2<i32>) -> f32 {
    let q = clamp(p, vec2<i32>(0), frame_size() - 1);
    return floor(liquid_layer(q) * 255.0);
}

fn pixel(p: vec2<i32>, w: Window) {
    let gx = (w.r.x + 2.0 * w.r.y + w.r.z) - (w.l.x + 2.0 * w.l.y + w.l.z);
    let gy = (w.l.z + 2.0 * w.c.z + w.r.z) - (w.l.x + 2.0 * w.c.x + w.r.x);
    let packed = (u32(i32(gx)) & 0xffffu) | (u32(i32(gy)) << 16u);
    textureStore(output, p, vec4<u32>(packed, 0u, 0u, 0u));
}
