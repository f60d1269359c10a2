// spatter (water), pass 5: OpenCV Canny's gradient on the 8-bit liquid layer: Sobel 3x3 (edges
// replicated), written as (L1 magnitude, gx, gy) for the non-maximum suppression of pass 6.
#include "perturb/image/window_runs.wgsl"
#include "perturb/image/spatter_layer.wgsl"

@group(0) @binding(0) var blurred: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba32float, write>;
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
    textureStore(output, p, vec4<f32>(abs(gx) + abs(gy), gx, gy, 0.0));
}
