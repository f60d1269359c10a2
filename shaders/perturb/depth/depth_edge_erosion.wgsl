// depth_edge_erosion: Canny edges of the depth normalised to 8 bits (Sobel 3x3 with replicated
// borders, L1 magnitude, OpenCV's non-maximum suppression, hysteresis), then every edge pixel and
// a 7x7 square around a `rate` fraction of them become invalid. Mirrored by
// crates/perturb/src/depth/depth_edge_erosion.rs; the entry points run in this order:
//   depth_max -> gradient -> suppress -> (plan_hysteresis -> hysteresis) xN, ping-pong ->
//   choose -> void_rows -> void_columns
// States: 0 none, 1 weak, 2 edge, 3 edge chosen for a 7x7 square.

struct Params {
    key: vec4<u32>,
    // x: rate, y: low threshold, z: high threshold
    values: vec4<f32>,
}

@group(0) @binding(0) var depth: texture_storage_2d<r32float, read_write>;
@group(0) @binding(1) var<uniform> params: Params;
// max depth as f32 bits (positive floats order like their bits)
@group(0) @binding(2) var<storage, read_write> max_bits: atomic<u32>;
@group(0) @binding(3) var state_in: texture_2d<f32>;
@group(0) @binding(4) var state_out: texture_storage_2d<r32float, write>;
// set when the last pass left weak pixels that may still join an edge
@group(0) @binding(5) var<storage, read_write> changed: atomic<u32>;
// indirect dispatch size of the next hysteresis pass
@group(0) @binding(6) var<storage, read_write> next_pass: array<u32, 3>;

#include "common/rng.wgsl"

// One invocation per column (no workgroup barriers: slow on CPU Vulkan).
@compute @workgroup_size(64)
fn depth_max(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(depth);
    if (id.x >= size.x) {
        return;
    }
    var column_max = 0.0;
    for (var y = 0u; y < size.y; y++) {
        column_max = max(column_max, textureLoad(depth, vec2<u32>(id.x, y)).x);
    }
    atomicMax(&max_bits, bitcast<u32>(column_max));
}

fn depth8(p: vec2<i32>, size: vec2<i32>, scale: f32) -> i32 {
    let q = clamp(p, vec2<i32>(0), size - 1);
    return i32(floor(textureLoad(depth, vec2<u32>(q)).x * scale));
}

// Writes direction * 4096 + magnitude; directions as OpenCV: 0 compare left/right, 1 up/down,
// 2 diagonal (x-1,y-1)/(x+1,y+1), 3 diagonal (x+1,y-1)/(x-1,y+1).
@compute @workgroup_size(8, 8)
fn gradient(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(depth));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    let z_max = bitcast<f32>(atomicLoad(&max_bits));
    var scale = 0.0;
    if (z_max > 0.0) {
        scale = 255.0 / z_max;
    }
    let a = depth8(p + vec2<i32>(-1, -1), size, scale);
    let b = depth8(p + vec2<i32>(0, -1), size, scale);
    let c = depth8(p + vec2<i32>(1, -1), size, scale);
    let d = depth8(p + vec2<i32>(-1, 0), size, scale);
    let f = depth8(p + vec2<i32>(1, 0), size, scale);
    let g = depth8(p + vec2<i32>(-1, 1), size, scale);
    let h = depth8(p + vec2<i32>(0, 1), size, scale);
    let i = depth8(p + vec2<i32>(1, 1), size, scale);
    let dx = (c + 2 * f + i) - (a + 2 * d + g);
    let dy = (g + 2 * h + i) - (a + 2 * b + c);
    let xs = abs(dx);
    let ys = abs(dy);
    // tan(22.5°) in Q15, as OpenCV's Canny.
    let tg22x = xs * 13573;
    let y = ys << 15u;
    var direction = 0;
    if (y >= tg22x) {
        if (y > tg22x + (xs << 16u)) {
            direction = 1;
        } else if ((dx ^ dy) < 0) {
            direction = 3;
        } else {
            direction = 2;
        }
    }
    textureStore(state_out, id.xy, vec4<f32>(f32(direction * 4096 + xs + ys)));
}

fn magnitude(p: vec2<i32>, size: vec2<i32>) -> i32 {
    if (p.x < 0 || p.y < 0 || p.x >= size.x || p.y >= size.y) {
        return 0;
    }
    return i32(textureLoad(state_in, p, 0).x) % 4096;
}

@compute @workgroup_size(8, 8)
fn suppress(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(state_in));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    let code = i32(textureLoad(state_in, p, 0).x);
    let m = code % 4096;
    let direction = code / 4096;
    var state = 0.0;
    if (f32(m) > params.values.y) {
        var keep: bool;
        switch (direction) {
            case 0: {
                keep = m > magnitude(p + vec2<i32>(-1, 0), size) && m >= magnitude(p + vec2<i32>(1, 0), size);
            }
            case 1: {
                keep = m > magnitude(p + vec2<i32>(0, -1), size) && m >= magnitude(p + vec2<i32>(0, 1), size);
            }
            case 2: {
                keep = m > magnitude(p + vec2<i32>(-1, -1), size) && m > magnitude(p + vec2<i32>(1, 1), size);
            }
            default: {
                keep = m > magnitude(p + vec2<i32>(1, -1), size) && m > magnitude(p + vec2<i32>(-1, 1), size);
            }
        }
        if (keep) {
            state = select(1.0, 2.0, f32(m) > params.values.z);
            if (state == 1.0) {
                atomicStore(&changed, 1u);
            }
        }
    }
    textureStore(state_out, id.xy, vec4<f32>(state));
}

// Hysteresis, one global pass: each 16x16 tile floods "edge" into its weak pixels until the
// tile is stable, seeded by edges inside the tile and in its one-pixel halo (the halo is read,
// never written). Repeated passes carry edges across tiles. A pass that changes nothing leaves
// its output equal to its input, so `plan_hysteresis` skips every later pass (dispatch size 0).
const TILE: u32 = 16u;
const SPAN: u32 = 18u;
var<workgroup> tile: array<u32, 324>;
var<workgroup> tile_flag: atomic<u32>;
var<workgroup> tile_go: u32;

// Whether any invocation raised tile_flag since the last call (clears it); a barrier for all.
fn tile_flag_raised(lane: u32) -> bool {
    workgroupBarrier();
    if (lane == 0u) {
        tile_go = atomicExchange(&tile_flag, 0u);
    }
    return workgroupUniformLoad(&tile_go) != 0u;
}

@compute @workgroup_size(16, 16)
fn hysteresis(
    @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
    @builtin(workgroup_id) group: vec3<u32>,
) {
    let size = vec2<i32>(textureDimensions(state_in));
    let origin = vec2<i32>(group.xy * TILE) - vec2<i32>(1);
    for (var i = lane; i < SPAN * SPAN; i += TILE * TILE) {
        let offset = vec2<i32>(i32(i % SPAN), i32(i / SPAN));
        let p = origin + offset;
        var s = 0u;
        if (p.x >= 0 && p.y >= 0 && p.x < size.x && p.y < size.y) {
            s = u32(textureLoad(state_in, p, 0).x);
        }
        tile[i] = s;
        let interior = offset.x >= 1 && offset.y >= 1 && offset.x <= i32(TILE) && offset.y <= i32(TILE);
        if (s == 1u && interior) {
            atomicStore(&tile_flag, 1u);
        }
    }
    let has_weak = tile_flag_raised(lane);
    let me = (local.y + 1u) * SPAN + local.x + 1u;
    var tile_changed = false;
    if (has_weak) {
        for (var iteration = 0u; iteration < TILE * TILE; iteration++) {
            var promote = false;
            if (tile[me] == 1u) {
                promote = tile[me - SPAN - 1u] == 2u || tile[me - SPAN] == 2u || tile[me - SPAN + 1u] == 2u
                    || tile[me - 1u] == 2u || tile[me + 1u] == 2u
                    || tile[me + SPAN - 1u] == 2u || tile[me + SPAN] == 2u || tile[me + SPAN + 1u] == 2u;
            }
            workgroupBarrier();
            if (promote) {
                tile[me] = 2u;
                atomicStore(&tile_flag, 1u);
            }
            if (!tile_flag_raised(lane)) {
                break;
            }
            tile_changed = true;
        }
    }
    let p = vec2<i32>(group.xy * TILE + local.xy);
    if (p.x < size.x && p.y < size.y) {
        textureStore(state_out, vec2<u32>(p), vec4<f32>(f32(tile[me])));
    }
    if (tile_changed && lane == 0u) {
        atomicStore(&changed, 1u);
    }
}

// Sizes the next hysteresis pass: all tiles if the last pass (or `suppress`) changed
// something, none otherwise.
@compute @workgroup_size(1)
fn plan_hysteresis() {
    let tiles = (textureDimensions(state_in) + vec2<u32>(TILE - 1u)) / TILE;
    let go = atomicExchange(&changed, 0u) != 0u;
    next_pass[0] = select(0u, tiles.x, go);
    next_pass[1] = select(0u, tiles.y, go);
    next_pass[2] = 1u;
}

// Edges stay (2) or are chosen (3) with probability `rate`; weak pixels never reached vanish.
@compute @workgroup_size(8, 8)
fn choose(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(state_in);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    var state = 0.0;
    if (textureLoad(state_in, id.xy, 0).x == 2.0) {
        let u = rng_uniform(rng_draw(params.key, vec4<u32>(id.x, id.y, 0u, 0u)).x);
        state = select(2.0, 3.0, u < params.values.x);
    }
    textureStore(state_out, id.xy, vec4<f32>(state));
}

// bit 0: the pixel is an edge; bit 1: a chosen edge lies within 3 pixels along the row.
@compute @workgroup_size(8, 8)
fn void_rows(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(state_in));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    var bits = select(0u, 1u, textureLoad(state_in, p, 0).x >= 2.0);
    for (var dx = -3; dx <= 3; dx++) {
        let x = p.x + dx;
        if (x >= 0 && x < size.x && textureLoad(state_in, vec2<i32>(x, p.y), 0).x == 3.0) {
            bits |= 2u;
        }
    }
    textureStore(state_out, id.xy, vec4<f32>(f32(bits)));
}

@compute @workgroup_size(8, 8)
fn void_columns(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(state_in));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    var erase = (u32(textureLoad(state_in, p, 0).x) & 1u) != 0u;
    for (var dy = -3; dy <= 3; dy++) {
        let y = p.y + dy;
        if (y >= 0 && y < size.y && (u32(textureLoad(state_in, vec2<i32>(p.x, y), 0).x) & 2u) != 0u) {
            erase = true;
        }
    }
    if (erase) {
        textureStore(depth, id.xy, vec4<f32>(0.0));
    }
}
