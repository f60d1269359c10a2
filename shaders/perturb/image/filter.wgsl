// Helpers shared by the filtering corruptions (blurs, glass, snow, spatter, elastic).

// A weighted sum of a flat region comes out a few f32 ulps below the input level, which
// truncation to 8 bits would turn into one level less; imagecorruptions computes in float64 and
// keeps the level. Adding 1/1000 of a level before truncating restores that.
const SUM_EPSILON: f32 = 4e-6;

// A symmetric 1-D kernel for passes that write runs of 8 outputs per invocation
// (filter_rows, filter_columns): taps[i].x is the weight at offset i - 8 - radius,
// zero outside the kernel; `count` (a multiple of 8, at least 2 radius + 8) source pixels are read
// per run, 8 per loop iteration. Output o of a run takes source j + m with weight
// taps[j + m - o + 8]. Each source texel is read once per run and the loop costs one iteration
// per 8 of them; on lavapipe loop iterations and per-invocation overhead dominate texture loads,
// and this is 3-8x faster than one output per invocation.
struct Kernel1d {
    radius: i32,
    count: i32,
    // filter_rows / filter_columns: 0 = replicate edges, 1 = reflect (half-sample symmetric)
    edge: i32,
    _pad1: i32,
    taps: array<vec4<f32>, 256>,
}

// Line taps of imagecorruptions' motion blur (motion_blur, snow): tap k reads offset
// (taps[k].x, taps[k].y) with weight taps[k].z; `count` taps.
struct LineKernel {
    count: i32,
    _pad0: i32,
    _pad1: i32,
    _pad2: i32,
    taps: array<vec4<f32>, 48>,
}
