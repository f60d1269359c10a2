// pixelate (imagecorruptions `pixelate`): PIL BOX downscale to (int(W*c), int(H*c)), then PIL
// NEAREST upscale back, in PIL's 8-bit fixed-point arithmetic. Index tables come from
// crates/perturb/src/image/pixelate.rs (PIL's rounding of box supports and nearest positions).
// Entry `box_rows`: horizontal box pass, frame -> intermediate (w' x H).
// Entry `main`, one invocation per small pixel: vertical box pass, then the value is written to
// the block of frame pixels whose nearest source it is, intermediate -> frame.

struct Params {
    // x: small width w', y: small height h', z: frame width W, w: frame height H
    sizes: vec4<u32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Params;
// [column box runs (w'), row box runs (h'), column blocks (w'), row blocks (h')]; a run or block
// packs start | count << 16.
@group(0) @binding(3) var<storage, read> tables: array<u32>;

// PIL's PRECISION_BITS for 8-bit resampling.
const PRECISION_BITS: u32 = 22u;

fn load8(p: vec2<u32>) -> vec3<u32> {
    return vec3<u32>(round(textureLoad(source, p, 0).rgb * 255.0));
}

// PIL: coefficient (int)(0.5 + 2^22 / n); output (2^21 + sum) >> 22, clipped to 8 bits.
fn box_average(sum: vec3<u32>, count: u32) -> vec4<f32> {
    let weight = ((1u << (PRECISION_BITS + 1u)) + count) / (2u * count);
    let value = ((1u << (PRECISION_BITS - 1u)) + sum * weight) >> vec3<u32>(PRECISION_BITS);
    return vec4<f32>(vec3<f32>(min(value, vec3<u32>(255u))) / 255.0, 1.0);
}

@compute @workgroup_size(8, 8)
fn box_rows(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.sizes.x || id.y >= params.sizes.w) {
        return;
    }
    let range = tables[id.x];
    let start = range & 0xffffu;
    let count = range >> 16u;
    var sum = vec3<u32>(0u);
    for (var i = 0u; i < count; i++) {
        sum += load8(vec2<u32>(start + i, id.y));
    }
    textureStore(output, id.xy, box_average(sum, count));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let small_w = params.sizes.x;
    let small_h = params.sizes.y;
    if (id.x >= small_w || id.y >= small_h) {
        return;
    }
    let run = tables[small_w + id.y];
    let start = run & 0xffffu;
    let count = run >> 16u;
    var sum = vec3<u32>(0u);
    for (var i = 0u; i < count; i++) {
        sum += load8(vec2<u32>(id.x, start + i));
    }
    let value = box_average(sum, count);
    let columns = tables[small_w + small_h + id.x];
    let rows = tables[2u * small_w + small_h + id.y];
    let x0 = columns & 0xffffu;
    let y0 = rows & 0xffffu;
    for (var y = y0; y < y0 + (rows >> 16u); y++) {
        for (var x = x0; x < x0 + (columns >> 16u); x++) {
            textureStore(output, vec2<u32>(x, y), value);
        }
    }
}
