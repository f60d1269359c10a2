// jpeg_compression, pass 2 of 2: decode side of the round trip as libjpeg-turbo does it:
// "fancy" h2v2 chroma upsampling (jdsample.c: triangle filter, 3/4 near + 1/4 far per axis,
// rounding biases 8 and 7, edges replicated) and YCbCr -> RGB with jdcolor.c's fixed-point
// tables, clamped to 0..255. Each invocation decodes the 2x2 pixels of one chroma sample, which
// share the 3x3 chroma samples around it.

@group(0) @binding(0) var luma: texture_2d<u32>;
@group(0) @binding(1) var chroma: texture_2d<u32>;
@group(0) @binding(2) var output: texture_storage_2d<rgba8unorm, write>;

var<private> chroma_last: vec2<i32>;

fn sample(x: i32, y: i32, plane_offset: i32) -> i32 {
    let q = clamp(vec2<i32>(x, y), vec2<i32>(0), chroma_last);
    return i32(textureLoad(chroma, vec2<i32>(q.x + plane_offset, q.y), 0).r);
}

// Column x of one plane at rows c.y - 1, c.y and c.y + 1, each row as near 3/4 + far 1/4: .x for
// the even pixel row (far row above), .y for the odd one (far row below).
fn column(x: i32, y: i32, plane_offset: i32) -> vec2<i32> {
    let above = sample(x, y - 1, plane_offset);
    let near = 3 * sample(x, y, plane_offset);
    let below = sample(x, y + 1, plane_offset);
    return vec2<i32>(near + above, near + below);
}

// The chroma values of one plane at the 2x2 pixels of chroma sample c: (x even, y even),
// (odd, even), (even, odd), (odd, odd).
fn upsample(c: vec2<i32>, plane_offset: i32) -> vec4<i32> {
    let left = column(c.x - 1, c.y, plane_offset);
    let middle = column(c.x, c.y, plane_offset);
    let right = column(c.x + 1, c.y, plane_offset);
    let even = (3 * middle + left + 8) >> vec2<u32>(4u);
    let odd = (3 * middle + right + 7) >> vec2<u32>(4u);
    return vec4<i32>(even.x, odd.x, even.y, odd.y);
}

fn store(p: vec2<i32>, size: vec2<i32>, y: i32, cb: i32, cr: i32) {
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    // jdcolor.c: FIX(1.402) = 91881, FIX(1.772) = 116130, FIX(0.71414) = 46802,
    // FIX(0.34414) = 22554, ONE_HALF = 32768.
    let r = y + ((91881 * cr + 32768) >> 16u);
    let g = y + ((-22554 * cb + 32768 - 46802 * cr) >> 16u);
    let b = y + ((116130 * cb + 32768) >> 16u);
    let rgb = clamp(vec3<i32>(r, g, b), vec3<i32>(0), vec3<i32>(255));
    textureStore(output, p, vec4<f32>(vec3<f32>(rgb) / 255.0, 1.0));
}

fn luma_at(p: vec2<i32>) -> i32 {
    return i32(textureLoad(luma, p, 0).r);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(output));
    // Chroma planes hold ceil(W/2) x ceil(H/2) real samples; Cr starts at half the width.
    chroma_last = (size + 1) / 2 - 1;
    let c = vec2<i32>(id.xy);
    if (c.x > chroma_last.x || c.y > chroma_last.y) {
        return;
    }
    let cb = upsample(c, 0) - 128;
    let cr = upsample(c, i32(textureDimensions(chroma).x) / 2) - 128;
    // The luma texture covers whole MCUs, so the 2x2 pixels can be read at the frame's edge.
    let p = 2 * c;
    store(p, size, luma_at(p), cb.x, cr.x);
    store(p + vec2<i32>(1, 0), size, luma_at(p + vec2<i32>(1, 0)), cb.y, cr.y);
    store(p + vec2<i32>(0, 1), size, luma_at(p + vec2<i32>(0, 1)), cb.z, cr.z);
    store(p + vec2<i32>(1, 1), size, luma_at(p + vec2<i32>(1, 1)), cb.w, cr.w);
}
