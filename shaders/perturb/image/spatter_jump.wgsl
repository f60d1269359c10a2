// spatter (water), passes 7-11: one jump-flooding step (Rong & Tan 2006): each pixel keeps the
// nearest of the seeds found at offsets {-k, 0, k}^2. Steps 16, 8, 4, 2, 1 find every edge within
// the 20 pixels the distance is truncated at.

struct Jump {
    step: i32,
    _pad0: i32,
    _pad1: i32,
    _pad2: i32,
}

@group(0) @binding(0) var source: texture_2d<u32>;
@group(0) @binding(1) var output: texture_storage_2d<r32uint, write>;
@group(0) @binding(2) var<uniform> jump: Jump;

const NONE: u32 = 0xffffffffu;

fn unpack(seed: u32) -> vec2<i32> {
    return vec2<i32>(i32(seed & 0xffffu), i32(seed >> 16u));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    var best = textureLoad(source, p, 0).x;
    var best_distance = 1e30;
    if (best != NONE) {
        let d = vec2<f32>(unpack(best) - p);
        best_distance = dot(d, d);
    }
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let q = p + jump.step * vec2<i32>(dx, dy);
            if (any(q < vec2<i32>(0)) || any(q >= size)) {
                continue;
            }
            let seed = textureLoad(source, q, 0).x;
            if (seed == NONE) {
                continue;
            }
            let d = vec2<f32>(unpack(seed) - p);
            let distance = dot(d, d);
            if (distance < best_distance) {
                best = seed;
                best_distance = distance;
            }
        }
    }
    textureStore(output, p, vec4<u32>(best, 0u, 0u, 0u));
}
