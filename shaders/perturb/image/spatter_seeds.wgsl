// spatter (water), pass 6: Canny's hysteresis, one step (a weak edge survives next to a strong
// one), as the input of the distance transform: 0 on an edge, NONE (no edge) elsewhere.

@group(0) @binding(0) var classes: texture_2d<f32>;
@group(0) @binding(1) var seeds: texture_storage_2d<r32uint, write>;

// spatter_squared_distance.wgsl's NONE.
const NONE: u32 = 1024u;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(classes));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    let kind = textureLoad(classes, p, 0).x;
    var edge = kind == 2.0;
    if (kind == 1.0) {
        for (var dy = -1; dy <= 1; dy++) {
            for (var dx = -1; dx <= 1; dx++) {
                let q = clamp(p + vec2<i32>(dx, dy), vec2<i32>(0), size - 1);
                edge = edge || textureLoad(classes, q, 0).x == 2.0;
            }
        }
    }
    textureStore(seeds, p, vec4<u32>(select(NONE, 0u, edge), 0u, 0u, 0u));
}
