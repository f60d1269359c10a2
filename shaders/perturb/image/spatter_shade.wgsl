// spatter (water), pass 14: 3x3 box mean of the embossed distance (cv2.blur on 8 bits: rounded,
// BORDER_REFLECT_101) times the 8-bit liquid layer; the maximum goes to an atomic (the values are
// non-negative, so their f32 bits order like the values), once per run of 8 pixels: one address
// updated by every pixel is contended by every core.
#include "perturb/image/window_runs.wgsl"
#include "perturb/image/spatter_layer.wgsl"

@group(0) @binding(0) var embossed: texture_2d<f32>;
@group(0) @binding(1) var blurred: texture_2d<f32>;
@group(0) @binding(2) var output: texture_storage_2d<r32float, write>;
@group(0) @binding(3) var<storage, read_write> maximum: array<atomic<u32>, 4>;
@group(0) @binding(4) var<uniform> liquid: Liquid;

fn frame_size() -> vec2<i32> {
    return vec2<i32>(textureDimensions(embossed));
}

fn sample(p: vec2<i32>) -> f32 {
    let size = frame_size();
    return textureLoad(embossed, (size - 1) - abs((size - 1) - abs(p)), 0).x;
}

// The largest value of the run so far.
var<private> run_maximum: f32;

fn pixel(p: vec2<i32>, w: Window) {
    // In row order, as the twin sums.
    let sum = w.l.x + w.c.x + w.r.x + w.l.y + w.c.y + w.r.y + w.l.z + w.c.z + w.r.z;
    let shade = round(sum / 9.0);
    let m = floor(liquid_layer(p) * 255.0) * shade;
    run_maximum = select(max(run_maximum, m), m, p.x % 8 == 0);
    if (p.x % 8 == 7 || p.x == frame_size().x - 1) {
        atomicMax(&maximum[0], bitcast<u32>(run_maximum));
    }
    textureStore(output, p, vec4<f32>(m, 0.0, 0.0, 0.0));
}
