// motion_blur: imagecorruptions' one-sided line kernel. Tap i reads the source at the integer
// offset (dx_i, dy_i) along the frame's angle with weight exp(-i²/2σ²) (normalised); edges
// replicated; truncated to 8 bits. Offsets and weights are computed on the CPU per frame.
#include "common/color.wgsl"
#include "perturb/image/filter.wgsl"

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> line: LineKernel;

fn tap(k: i32, p: vec2<i32>, last: vec2<i32>) -> vec3<f32> {
    let t = line.taps[k];
    let q = clamp(p + vec2<i32>(t.xy), vec2<i32>(0), last);
    return t.z * textureLoad(source, q, 0).rgb;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    let last = size - 1;
    var sum = vec3<f32>(0.0);
    for (var k = 0; k < line.count; k += 8) {
        sum += tap(k, p, last) + tap(k + 1, p, last) + tap(k + 2, p, last) + tap(k + 3, p, last);
        sum += tap(k + 4, p, last) + tap(k + 5, p, last) + tap(k + 6, p, last) + tap(k + 7, p, last);
    }
    textureStore(output, p, vec4<f32>(truncate8(sum + SUM_EPSILON), 1.0));
}
