// spatter (water), pass 6: OpenCV Canny's non-maximum suppression of pass 5's gradient in four
// directions (neighbours outside the image count as 0) and its thresholds 50 / 150. Writes 2
// (strong), 1 (weak) or 0.
#include "perturb/image/window_runs.wgsl"

@group(0) @binding(0) var gradient: texture_2d<u32>;
@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;

const LOW: i32 = 50;
const HIGH: i32 = 150;
// tan(22.5 deg) in Q15, as OpenCV's TG22.
const TG22: i32 = 13573;

fn frame_size() -> vec2<i32> {
    return vec2<i32>(textureDimensions(gradient));
}

// (gx, gy) from the 16-bit halves spatter_edges.wgsl packs.
fn gradient_at(p: vec2<i32>) -> vec2<i32> {
    let packed = i32(textureLoad(gradient, p, 0).x);
    return vec2<i32>((packed << 16u) >> 16u, packed >> 16u);
}

// The L1 magnitude.
fn sample(p: vec2<i32>) -> f32 {
    if (any(p < vec2<i32>(0)) || any(p >= frame_size())) {
        return 0.0;
    }
    let g = gradient_at(p);
    return f32(abs(g.x) + abs(g.y));
}

fn pixel(p: vec2<i32>, w: Window) {
    let m = w.c.y;
    var kind = 0.0;
    if (m > f32(LOW)) {
        let g = gradient_at(p);
        let ax = abs(g.x);
        let ay = abs(g.y) << 15u;
        let tg22x = ax * TG22;
        var maximum = false;
        if (ay < tg22x) {
            maximum = m > w.l.y && m >= w.r.y;
        } else if (ay > tg22x + (ax << 16u)) {
            maximum = m > w.c.x && m >= w.c.z;
        } else if ((g.x ^ g.y) < 0) {
            // s = -1: neighbours (1, -1) and (-1, 1)
            maximum = m > w.r.x && m > w.l.z;
        } else {
            maximum = m > w.l.x && m > w.r.z;
        }
        if (maximum) {
            kind = select(1.0, 2.0, m > f32(HIGH));
        }
    }
    textureStore(output, p, vec4<f32>(kind, 0.0, 0.0, 0.0));
}
