// jpeg_compression, pass 1 of 2: the lossy part of a baseline JPEG round trip as libjpeg-turbo
// (Pillow's codec) does it, in the same integer arithmetic: RGB -> YCbCr (jccolor.c), 2x2 chroma
// averaging with alternating bias (jcsample.c h2v2), 8x8 accurate-integer forward DCT
// (jfdctint.c), quantisation with rounding, dequantisation and accurate-integer inverse DCT
// (jidctint.c). The image is extended by edge replication to whole 16x16 MCUs. One invocation
// per 8x8 luma block, z = 0..3 the four of an MCU, and at z = 4 one for both chroma blocks, which
// share the 2x2 averages of the same pixels.

struct Tables {
    // Quantisation tables in natural (row-major) order: luma [0, 16), chroma [16, 32).
    quant: array<vec4<i32>, 32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var luma: texture_storage_2d<r32uint, write>;
// Cb in columns [0, W16/2), Cr in [W16/2, W16).
@group(0) @binding(2) var chroma: texture_storage_2d<r32uint, write>;
@group(0) @binding(3) var<uniform> tables: Tables;

const CONST_BITS: i32 = 13;
const PASS1_BITS: i32 = 2;

fn descale(x: i32, n: i32) -> i32 {
    return (x + (1 << u32(n - 1))) >> u32(n);
}

fn rgb_at(p: vec2<i32>) -> vec3<i32> {
    let size = vec2<i32>(textureDimensions(source));
    let q = clamp(p, vec2<i32>(0), size - 1);
    return vec3<i32>(round(textureLoad(source, q, 0).rgb * 255.0));
}

// jccolor.c: FIX(x) = round(x * 65536); Cb/Cr round with 0.5 - epsilon.
fn luma_of(c: vec3<i32>) -> i32 {
    return (19595 * c.r + 38470 * c.g + 7471 * c.b + 32768) >> 16u;
}

fn chroma_of(c: vec3<i32>) -> vec2<i32> {
    let offset = (128 << 16u) + 32767;
    let cb = (-11059 * c.r - 21709 * c.g + 32768 * c.b + offset) >> 16u;
    let cr = (32768 * c.r - 27439 * c.g - 5329 * c.b + offset) >> 16u;
    return vec2<i32>(cb, cr);
}

// One 1-D pass of jfdctint.c; `first` selects the row pass scaling.
fn fdct8(d: array<i32, 8>, first: bool) -> array<i32, 8> {
    var o: array<i32, 8>;
    let tmp0 = d[0] + d[7];
    let tmp7 = d[0] - d[7];
    let tmp1 = d[1] + d[6];
    let tmp6 = d[1] - d[6];
    let tmp2 = d[2] + d[5];
    let tmp5 = d[2] - d[5];
    let tmp3 = d[3] + d[4];
    let tmp4 = d[3] - d[4];
    let tmp10 = tmp0 + tmp3;
    let tmp13 = tmp0 - tmp3;
    let tmp11 = tmp1 + tmp2;
    let tmp12 = tmp1 - tmp2;
    var shift = CONST_BITS + PASS1_BITS;
    if (first) {
        o[0] = (tmp10 + tmp11) << u32(PASS1_BITS);
        o[4] = (tmp10 - tmp11) << u32(PASS1_BITS);
        shift = CONST_BITS - PASS1_BITS;
    } else {
        o[0] = descale(tmp10 + tmp11, PASS1_BITS);
        o[4] = descale(tmp10 - tmp11, PASS1_BITS);
    }
    let z1 = (tmp12 + tmp13) * 4433;
    o[2] = descale(z1 + tmp13 * 6270, shift);
    o[6] = descale(z1 - tmp12 * 15137, shift);
    let z5 = (tmp4 + tmp5 + tmp6 + tmp7) * 9633;
    let a4 = tmp4 * 2446;
    let a5 = tmp5 * 16819;
    let a6 = tmp6 * 25172;
    let a7 = tmp7 * 12299;
    let b1 = (tmp4 + tmp7) * -7373;
    let b2 = (tmp5 + tmp6) * -20995;
    let b3 = (tmp4 + tmp6) * -16069 + z5;
    let b4 = (tmp5 + tmp7) * -3196 + z5;
    o[7] = descale(a4 + b1 + b3, shift);
    o[5] = descale(a5 + b2 + b4, shift);
    o[3] = descale(a6 + b2 + b3, shift);
    o[1] = descale(a7 + b1 + b4, shift);
    return o;
}

// One 1-D pass of jidctint.c (inputs already dequantised); `shift` is the pass's descale.
fn idct8(d: array<i32, 8>, shift: i32) -> array<i32, 8> {
    var o: array<i32, 8>;
    let z1 = (d[2] + d[6]) * 4433;
    let tmp2 = z1 - d[6] * 15137;
    let tmp3 = z1 + d[2] * 6270;
    let tmp0 = (d[0] + d[4]) << u32(CONST_BITS);
    let tmp1 = (d[0] - d[4]) << u32(CONST_BITS);
    let tmp10 = tmp0 + tmp3;
    let tmp13 = tmp0 - tmp3;
    let tmp11 = tmp1 + tmp2;
    let tmp12 = tmp1 - tmp2;
    let i0 = d[7];
    let i1 = d[5];
    let i2 = d[3];
    let i3 = d[1];
    let z5 = (i0 + i1 + i2 + i3) * 9633;
    let c1 = (i0 + i3) * -7373;
    let c2 = (i1 + i2) * -20995;
    let c3 = (i0 + i2) * -16069 + z5;
    let c4 = (i1 + i3) * -3196 + z5;
    let e0 = i0 * 2446 + c1 + c3;
    let e1 = i1 * 16819 + c2 + c4;
    let e2 = i2 * 25172 + c2 + c3;
    let e3 = i3 * 12299 + c1 + c4;
    o[0] = descale(tmp10 + e3, shift);
    o[7] = descale(tmp10 - e3, shift);
    o[1] = descale(tmp11 + e2, shift);
    o[6] = descale(tmp11 - e2, shift);
    o[2] = descale(tmp12 + e1, shift);
    o[5] = descale(tmp12 - e1, shift);
    o[3] = descale(tmp13 + e0, shift);
    o[4] = descale(tmp13 - e0, shift);
    return o;
}

// libjpeg's post-IDCT range limit: table[x & 1023] (clamps x + 128 for |x| < 512).
fn range_limit(x: i32) -> u32 {
    let i = x & 1023;
    if (i < 128) {
        return u32(i + 128);
    }
    if (i < 512) {
        return 255u;
    }
    if (i < 896) {
        return 0u;
    }
    return u32(i - 896);
}

fn quant(table: i32, i: i32) -> i32 {
    return tables.quant[table * 16 + i / 4][i % 4];
}

// Level-shifted samples in, reconstructed samples out.
fn round_trip(samples: ptr<function, array<i32, 64>>, table: i32) {
    var row: array<i32, 8>;
    for (var r = 0; r < 8; r++) {
        for (var c = 0; c < 8; c++) {
            row[c] = (*samples)[r * 8 + c];
        }
        row = fdct8(row, true);
        for (var c = 0; c < 8; c++) {
            (*samples)[r * 8 + c] = row[c];
        }
    }
    for (var c = 0; c < 8; c++) {
        for (var r = 0; r < 8; r++) {
            row[r] = (*samples)[r * 8 + c];
        }
        row = fdct8(row, false);
        // Quantise (divisor 8q: the DCT output is scaled by 8; round half away from zero),
        // then dequantise for the IDCT.
        for (var r = 0; r < 8; r++) {
            let q = quant(table, r * 8 + c);
            let divisor = 8 * q;
            let level = (abs(row[r]) + (divisor >> 1u)) / divisor;
            (*samples)[r * 8 + c] = select(level, -level, row[r] < 0) * q;
        }
    }
    // jidctint.c: columns first, then rows.
    for (var c = 0; c < 8; c++) {
        for (var r = 0; r < 8; r++) {
            row[r] = (*samples)[r * 8 + c];
        }
        row = idct8(row, CONST_BITS - PASS1_BITS);
        for (var r = 0; r < 8; r++) {
            (*samples)[r * 8 + c] = row[r];
        }
    }
    for (var r = 0; r < 8; r++) {
        for (var c = 0; c < 8; c++) {
            row[c] = (*samples)[r * 8 + c];
        }
        row = idct8(row, CONST_BITS + PASS1_BITS + 3);
        for (var c = 0; c < 8; c++) {
            (*samples)[r * 8 + c] = row[c];
        }
    }
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let mcus = (vec2<u32>(textureDimensions(source)) + 15u) / 16u;
    if (id.x >= mcus.x || id.y >= mcus.y) {
        return;
    }
    let block = i32(id.z);
    var samples: array<i32, 64>;
    if (block < 4) {
        let origin = vec2<i32>(id.xy) * 16 + vec2<i32>(block % 2, block / 2) * 8;
        for (var i = 0; i < 64; i++) {
            samples[i] = luma_of(rgb_at(origin + vec2<i32>(i % 8, i / 8))) - 128;
        }
        round_trip(&samples, 0);
        for (var i = 0; i < 64; i++) {
            let p = origin + vec2<i32>(i % 8, i / 8);
            textureStore(luma, p, vec4<u32>(range_limit(samples[i]), 0u, 0u, 0u));
        }
        return;
    }
    let origin = vec2<i32>(id.xy) * 8;
    var cr: array<i32, 64>;
    for (var i = 0; i < 64; i++) {
        let c = origin + vec2<i32>(i % 8, i / 8);
        let p = 2 * c;
        let sum = chroma_of(rgb_at(p)) + chroma_of(rgb_at(p + vec2<i32>(1, 0)))
            + chroma_of(rgb_at(p + vec2<i32>(0, 1))) + chroma_of(rgb_at(p + vec2<i32>(1, 1)));
        // jcsample.c h2v2_downsample: bias 1, 2, 1, 2, ... along the row.
        let bias = 1 + (c.x & 1);
        let average = ((sum + bias) >> vec2<u32>(2u)) - 128;
        samples[i] = average.x;
        cr[i] = average.y;
    }
    round_trip(&samples, 1);
    round_trip(&cr, 1);
    // Cr starts at half the plane's width.
    let cr_offset = vec2<i32>(i32(mcus.x) * 8, 0);
    for (var i = 0; i < 64; i++) {
        let c = origin + vec2<i32>(i % 8, i / 8);
        textureStore(chroma, c, vec4<u32>(range_limit(samples[i]), 0u, 0u, 0u));
        textureStore(chroma, c + cr_offset, vec4<u32>(range_limit(cr[i]), 0u, 0u, 0u));
    }
}
