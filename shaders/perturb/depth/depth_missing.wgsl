// depth_missing: voids `count` rectangles drawn on the CPU (crates/perturb/src/depth/depth_missing.rs).
// Dispatched as (rectangle width / 8, rectangle height / 8, count): workgroup z is the rectangle.

struct Params {
    // x: number of rectangles
    count: vec4<u32>,
    // (x0, y0, x1, y1), half-open
    rects: array<vec4<u32>, 10>,
}

@group(0) @binding(0) var depth: texture_storage_2d<r32float, read_write>;
@group(0) @binding(1) var<uniform> params: Params;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let r = params.rects[id.z];
    let p = r.xy + id.xy;
    if (p.x < r.z && p.y < r.w) {
        textureStore(depth, p, vec4<f32>(0.0));
    }
}
