// spatter (water), pass 9: the squared distance to the nearest edge, truncated, as the second of
// two 1-D minimisations (Felzenszwalb & Huttenlocher 2012, "Distance transforms of sampled
// functions"): spatter_column_distance.wgsl gives each pixel its squared vertical distance to the
// nearest edge of its column; along rows, each output = min over offsets d of d^2 + that value
// at offset d, in integers: the squared Euclidean distance to the nearest edge (at least 400 =
// 20^2, the truncation, meaning "no edge within 20"). Positions outside the image hold no edge.
// Each invocation writes a run of 8 pixels of a row, reading each of the 48 source pixels it
// needs once. Offsets beyond 20 are not excluded: they add d^2 > 400, so they only change values
// the distance pass truncates to 400 anyway.

@group(0) @binding(0) var source: texture_2d<u32>;
@group(0) @binding(1) var output: texture_storage_2d<r32uint, write>;

const REACH: i32 = 20;
// More than REACH^2 + REACH^2: a pixel with no edge within REACH along either axis.
const NONE: u32 = 1024u;

// What source value v contributes at offset d.
fn cost(d: i32, v: u32) -> u32 {
    return u32(d * d) + v;
}

fn store(p: vec2<i32>, width: i32, best: u32) {
    if (p.x < width) {
        textureStore(output, p, vec4<u32>(min(best, NONE), 0u, 0u, 0u));
    }
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let x0 = i32(id.x) * 8;
    let y = i32(id.y);
    if (x0 >= size.x || y >= size.y) {
        return;
    }
    // The 8 outputs written out (loops over them are slow on lavapipe); source s is at offset
    // s - o from output o.
    var b0 = NONE;
    var b1 = NONE;
    var b2 = NONE;
    var b3 = NONE;
    var b4 = NONE;
    var b5 = NONE;
    var b6 = NONE;
    var b7 = NONE;
    for (var s = -REACH; s <= 7 + REACH; s++) {
        let x = x0 + s;
        if (x < 0 || x >= size.x) {
            continue;
        }
        let v = textureLoad(source, vec2<i32>(x, y), 0).x;
        b0 = min(b0, cost(s, v));
        b1 = min(b1, cost(s - 1, v));
        b2 = min(b2, cost(s - 2, v));
        b3 = min(b3, cost(s - 3, v));
        b4 = min(b4, cost(s - 4, v));
        b5 = min(b5, cost(s - 5, v));
        b6 = min(b6, cost(s - 6, v));
        b7 = min(b7, cost(s - 7, v));
    }
    store(vec2<i32>(x0, y), size.x, b0);
    store(vec2<i32>(x0 + 1, y), size.x, b1);
    store(vec2<i32>(x0 + 2, y), size.x, b2);
    store(vec2<i32>(x0 + 3, y), size.x, b3);
    store(vec2<i32>(x0 + 4, y), size.x, b4);
    store(vec2<i32>(x0 + 5, y), size.x, b5);
    store(vec2<i32>(x0 + 6, y), size.x, b6);
    store(vec2<i32>(x0 + 7, y), size.x, b7);
}
