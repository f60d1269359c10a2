// spatter (water), passes 8-9: the squared distance to the nearest edge, truncated, as two 1-D
// minimisations (Felzenszwalb & Huttenlocher 2012, "Distance transforms of sampled functions"):
// along columns, then along rows, each output = min over |d| <= 20 of d^2 + input at offset d,
// in integers. The seeds pass gives 0 on edges and NONE elsewhere; after columns each pixel
// holds its squared vertical distance to the nearest edge of its column, after rows the squared
// Euclidean distance to the nearest edge (at least 400 = 20^2, the truncation, meaning "no edge
// within 20"). Positions outside the image hold no edge. Each invocation writes a run of 8
// pixels along the axis, reading each of the 48 source pixels it needs once.

struct Axis {
    // 0: along rows (x), 1: along columns (y)
    axis: i32,
    _pad0: i32,
    _pad1: i32,
    _pad2: i32,
}

@group(0) @binding(0) var source: texture_2d<u32>;
@group(0) @binding(1) var output: texture_storage_2d<r32uint, write>;
@group(0) @binding(2) var<uniform> params: Axis;

const REACH: i32 = 20;
// More than REACH^2 + REACH^2: a pixel with no edge within REACH along either axis.
const NONE: u32 = 1024u;

var<private> size: vec2<i32>;
var<private> along: vec2<i32>;

// What source value v contributes at offset d.
fn cost(d: i32, v: u32) -> u32 {
    return select(NONE, u32(d * d) + v, abs(d) <= REACH);
}

fn store(start: vec2<i32>, o: i32, best: u32) {
    let p = start + o * along;
    if (all(p < size)) {
        textureStore(output, p, vec4<u32>(min(best, NONE), 0u, 0u, 0u));
    }
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    size = vec2<i32>(textureDimensions(source));
    along = select(vec2<i32>(1, 0), vec2<i32>(0, 1), params.axis == 1);
    let across = vec2<i32>(1, 1) - along;
    // Run index along the axis, position across it.
    let run = select(i32(id.x), i32(id.y), params.axis == 1);
    let line = select(i32(id.y), i32(id.x), params.axis == 1);
    let start = run * 8 * along + line * across;
    let length = dot(size, along);
    if (run * 8 >= length || line >= dot(size, across)) {
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
        let i = run * 8 + s;
        if (i < 0 || i >= length) {
            continue;
        }
        let v = textureLoad(source, start + s * along, 0).x;
        b0 = min(b0, cost(s, v));
        b1 = min(b1, cost(s - 1, v));
        b2 = min(b2, cost(s - 2, v));
        b3 = min(b3, cost(s - 3, v));
        b4 = min(b4, cost(s - 4, v));
        b5 = min(b5, cost(s - 5, v));
        b6 = min(b6, cost(s - 6, v));
        b7 = min(b7, cost(s - 7, v));
    }
    store(start, 0, b0);
    store(start, 1, b1);
    store(start, 2, b2);
    store(start, 3, b3);
    store(start, 4, b4);
    store(start, 5, b5);
    store(start, 6, b6);
    store(start, 7, b7);
}
