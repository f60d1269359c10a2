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

// The best of the current seed and the one found at p + offset (nearer wins; ties keep the
// current one). Candidates are written out below: loops cost more than the work on lavapipe.
struct Candidate {
    seed: u32,
    distance: f32,
}

fn consider(best: Candidate, p: vec2<i32>, offset: vec2<i32>, size: vec2<i32>) -> Candidate {
    let q = p + jump.step * offset;
    if (any(q < vec2<i32>(0)) || any(q >= size)) {
        return best;
    }
    let seed = textureLoad(source, q, 0).x;
    if (seed == NONE) {
        return best;
    }
    let d = vec2<f32>(unpack(seed) - p);
    let distance = dot(d, d);
    if (distance < best.distance) {
        return Candidate(seed, distance);
    }
    return best;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    let own = textureLoad(source, p, 0).x;
    var best = Candidate(own, 1e30);
    if (own != NONE) {
        let d = vec2<f32>(unpack(own) - p);
        best.distance = dot(d, d);
    }
    best = consider(best, p, vec2<i32>(-1, -1), size);
    best = consider(best, p, vec2<i32>(0, -1), size);
    best = consider(best, p, vec2<i32>(1, -1), size);
    best = consider(best, p, vec2<i32>(-1, 0), size);
    best = consider(best, p, vec2<i32>(0, 0), size);
    best = consider(best, p, vec2<i32>(1, 0), size);
    best = consider(best, p, vec2<i32>(-1, 1), size);
    best = consider(best, p, vec2<i32>(0, 1), size);
    best = consider(best, p, vec2<i32>(1, 1), size);
    textureStore(output, p, vec4<u32>(best.seed, 0u, 0u, 0u));
}
