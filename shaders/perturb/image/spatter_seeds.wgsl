// spatter (water), pass 7: Canny's hysteresis, one step (a weak edge survives next to a strong
// one), as the input of the distance transform: 0 on an edge, NONE (no edge) elsewhere.
#include "perturb/image/window_runs.wgsl"

@group(0) @binding(0) var classes: texture_2d<f32>;
@group(0) @binding(1) var seeds: texture_storage_2d<r32uint, write>;

// spatter_column_distance.wgsl's and spatter_squared_distance.wgsl's NONE.
const NONE: u32 = 1024u;

fn frame_size() -> vec2<i32> {
    return vec2<i32>(textureDimensions(classes));
}

fn sample(p: vec2<i32>) -> f32 {
    return textureLoad(classes, clamp(p, vec2<i32>(0), frame_size() - 1), 0).x;
}

fn pixel(p: vec2<i32>, w: Window) {
    let strong = vec3<f32>(2.0);
    let near_strong = any(w.l == strong) || any(w.c == strong) || any(w.r == strong);
    let edge = w.c.y == 2.0 || (w.c.y == 1.0 && near_strong);
    textureStore(seeds, p, vec4<u32>(select(NONE, 0u, edge), 0u, 0u, 0u));
}
