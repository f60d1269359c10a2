// Helpers shared by the filtering corruptions (blurs, glass, snow, spatter, elastic).

// A weighted sum of a flat region comes out a few f32 ulps below the input level, which
// truncation to 8 bits would turn into one level less; imagecorruptions computes in float64 and
// keeps the level. Adding 1/1000 of a level before truncating restores that.
const SUM_EPSILON: f32 = 4e-6;

// A 1-D kernel of `count` taps (a multiple of 8, zero-padded) at offsets -radius, -radius+1, ...
// Loops over it go 8 taps per iteration, written out: on lavapipe a loop iteration costs far
// more than a texture load, and neither `const` arrays nor nested constant loops get unrolled.
struct Kernel1d {
    radius: i32,
    count: i32,
    // filter_rows / filter_columns: 0 = replicate edges, 1 = reflect (half-sample symmetric)
    edge: i32,
    _pad1: i32,
    // taps[k].x is the weight at offset k - radius.
    taps: array<vec4<f32>, 256>,
}

// The same kernel laid out for runs of 8 outputs per invocation (gaussian_blur): taps[i].x is
// the weight at offset i - 8 - radius, zero outside the kernel; `count` (a multiple of 8, at
// least 2 radius + 8) source pixels are read per run. A run reads each source pixel once and
// pays one loop iteration per 8 of them: ~3x faster on lavapipe than one output per invocation.

// Line taps of imagecorruptions' motion blur (motion_blur, snow): tap k reads offset
// (taps[k].x, taps[k].y) with weight taps[k].z; `count` is a multiple of 8, zero-padded.
struct LineKernel {
    count: i32,
    _pad0: i32,
    _pad1: i32,
    _pad2: i32,
    taps: array<vec4<f32>, 48>,
}
