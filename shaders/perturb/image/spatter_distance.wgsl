// spatter (water), pass 10: distance to the nearest edge truncated at 20 (cv2.threshold TRUNC),
// from the squared distances of spatter_squared_distance.wgsl; 3x3 box mean (cv2.blur,
// BORDER_REFLECT_101), truncated to 8 bits; counted into a histogram for equalizeHist.
#include "perturb/image/window_runs.wgsl"

@group(0) @binding(0) var squared: texture_2d<u32>;
@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;
@group(0) @binding(2) var<storage, read_write> histogram: array<atomic<u32>, 256>;

// TRUNCATE^2
const TRUNCATE_SQUARED: u32 = 400u;

fn frame_size() -> vec2<i32> {
    return vec2<i32>(textureDimensions(squared));
}

fn sample(p: vec2<i32>) -> f32 {
    let size = frame_size();
    let q = (size - 1) - abs((size - 1) - abs(p));
    return sqrt(f32(min(textureLoad(squared, q, 0).x, TRUNCATE_SQUARED)));
}

fn pixel(p: vec2<i32>, w: Window) {
    // In row order, as the twin sums.
    let sum = w.l.x + w.c.x + w.r.x + w.l.y + w.c.y + w.r.y + w.l.z + w.c.z + w.r.z;
    let value = floor(sum / 9.0);
    atomicAdd(&histogram[u32(value)], 1u);
    textureStore(output, p, vec4<f32>(value, 0.0, 0.0, 0.0));
}
