// spatter (water), pass 8: the squared distance to the nearest edge in the same column, truncated
// at REACH = 20 (NONE beyond), from the seeds pass (0 on an edge, NONE elsewhere). Each invocation
// writes a run of 8 pixels down a column. The seeds from 20 above the run to 20 below it become
// two bit masks, so the nearest edge above a pixel is the highest set bit at or before it and the
// nearest below the lowest at or after it: 48 loads and a few bit operations per run instead of
// 41 candidate distances per pixel. spatter_squared_distance.wgsl then minimises along rows.

@group(0) @binding(0) var seeds: texture_2d<u32>;
@group(0) @binding(1) var output: texture_storage_2d<r32uint, write>;

const REACH: i32 = 20;
// spatter_squared_distance.wgsl's NONE.
const NONE: u32 = 1024u;

var<private> column: i32;
var<private> height: i32;

// 1 where row y of the column is an edge, 0 elsewhere and outside the image.
fn edge_bit(y: i32) -> u32 {
    if (y < 0 || y >= height) {
        return 0u;
    }
    return select(0u, 1u, textureLoad(seeds, vec2<i32>(column, y), 0).x == 0u);
}

fn squared(distance: u32) -> u32 {
    return select(NONE, distance * distance, distance <= u32(REACH));
}

// Output o of the run: `above` has bit k for row o0 - 24 + k, `below` bit k for row o0 + k.
fn store(y0: i32, o: u32, above: u32, below: u32) {
    let y = y0 + i32(o);
    if (y >= height) {
        return;
    }
    // Rows after o shifted out: the highest remaining bit h is row y0 + o - 31 + h.
    let up = above << (7u - o);
    let up_distance = select(NONE, 31u - firstLeadingBit(up), up != 0u);
    let down = below >> o;
    let down_distance = select(NONE, firstTrailingBit(down), down != 0u);
    let nearest = min(squared(up_distance), squared(down_distance));
    textureStore(output, vec2<i32>(column, y), vec4<u32>(nearest, 0u, 0u, 0u));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(seeds));
    column = i32(id.x);
    height = size.y;
    let y0 = i32(id.y) * 8;
    if (column >= size.x || y0 >= height) {
        return;
    }
    // Rows y0 - 20 .. y0 + 7 into bits 4 .. 31 of `above`.
    var above = 0u;
    for (var k = 4; k < 32; k++) {
        above |= edge_bit(y0 - 24 + k) << u32(k);
    }
    // Rows y0 .. y0 + 7 are bits 24 .. 31 of `above`; rows y0 + 8 .. y0 + 27 are loaded.
    var below = above >> 24u;
    for (var k = 8; k < 8 + REACH; k++) {
        below |= edge_bit(y0 + k) << u32(k);
    }
    store(y0, 0u, above, below);
    store(y0, 1u, above, below);
    store(y0, 2u, above, below);
    store(y0, 3u, above, below);
    store(y0, 4u, above, below);
    store(y0, 5u, above, below);
    store(y0, 6u, above, below);
    store(y0, 7u, above, below);
}
