// jpeg_compression, pass 2 of 2: decode side of the round trip as libjpeg-turbo does it:
// "fancy" h2v2 chroma upsampling (jdsample.c: triangle filter, 3/4 near + 1/4 far per axis,
// rounding biases 8 and 7, edges replicated) and YCbCr -> RGB with jdcolor.c's fixed-point
// tables, clamped to 0..255.

@group(0) @binding(0) var luma: texture_2d<u32>;
@group(0) @binding(1) var chroma: texture_2d<u32>;
@group(0) @binding(2) var output: texture_storage_2d<rgba8unorm, write>;

var<private> chroma_last: vec2<i32>;
var<private> plane_offset: i32;

fn sample(c: vec2<i32>) -> i32 {
    let q = clamp(c, vec2<i32>(0), chroma_last);
    return i32(textureLoad(chroma, vec2<i32>(q.x + plane_offset, q.y), 0).r);
}

// The chroma value at full-resolution pixel p of one plane.
fn upsample(p: vec2<i32>) -> i32 {
    let c = p / 2;
    // The nearer row is c.y; the farther one is above for even rows, below for odd rows.
    let far_row = select(c.y + 1, c.y - 1, (p.y & 1) == 0);
    let this_sum = 3 * sample(c) + sample(vec2<i32>(c.x, far_row));
    if ((p.x & 1) == 0) {
        let left = 3 * sample(vec2<i32>(c.x - 1, c.y)) + sample(vec2<i32>(c.x - 1, far_row));
        return (3 * this_sum + left + 8) >> 4u;
    }
    let right = 3 * sample(vec2<i32>(c.x + 1, c.y)) + sample(vec2<i32>(c.x + 1, far_row));
    return (3 * this_sum + right + 7) >> 4u;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(output));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    // Chroma planes hold ceil(W/2) x ceil(H/2) real samples; Cr starts at half the width.
    chroma_last = (size + 1) / 2 - 1;
    plane_offset = 0;
    let cb = upsample(p) - 128;
    plane_offset = i32(textureDimensions(chroma).x) / 2;
    let cr = upsample(p) - 128;
    let y = i32(textureLoad(luma, p, 0).r);
    // jdcolor.c: FIX(1.402) = 91881, FIX(1.772) = 116130, FIX(0.71414) = 46802,
    // FIX(0.34414) = 22554, ONE_HALF = 32768.
    let r = y + ((91881 * cr + 32768) >> 16u);
    let g = y + ((-22554 * cb + 32768 - 46802 * cr) >> 16u);
    let b = y + ((116130 * cb + 32768) >> 16u);
    let rgb = clamp(vec3<i32>(r, g, b), vec3<i32>(0), vec3<i32>(255));
    textureStore(output, p, vec4<f32>(vec3<f32>(rgb) / 255.0, 1.0));
}
