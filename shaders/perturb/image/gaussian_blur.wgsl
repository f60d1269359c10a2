// gaussian_blur, pass 2 of 2: the vertical half of the separable Gaussian (edge replicate),
// from the f32 scratch to 8 bits by truncation, in runs of 8 pixels per invocation (see
// filter.wgsl). Also glass_blur's second pass.
#include "common/color.wgsl"
#include "perturb/image/filter.wgsl"
#include "perturb/image/kernel_run.wgsl"

alias Value = vec3<f32>;

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> kernel: Kernel1d;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let first = i32(id.y) * 8 - kernel.radius;
    let fixed = i32(id.x);
    let last = size.y - 1;
    let origin = i32(id.y) * 8;
    if (fixed >= size.x || origin >= size.y) {
        return;
    }
    var s0 = vec3<f32>(0.0);
    var s1 = vec3<f32>(0.0);
    var s2 = vec3<f32>(0.0);
    var s3 = vec3<f32>(0.0);
    var s4 = vec3<f32>(0.0);
    var s5 = vec3<f32>(0.0);
    var s6 = vec3<f32>(0.0);
    var s7 = vec3<f32>(0.0);
    for (var j = 0; j < kernel.count; j += 8) {
        let v0 = textureLoad(source, vec2<i32>(fixed, clamp(first + j + 0, 0, last)), 0).rgb;
        let v1 = textureLoad(source, vec2<i32>(fixed, clamp(first + j + 1, 0, last)), 0).rgb;
        let v2 = textureLoad(source, vec2<i32>(fixed, clamp(first + j + 2, 0, last)), 0).rgb;
        let v3 = textureLoad(source, vec2<i32>(fixed, clamp(first + j + 3, 0, last)), 0).rgb;
        let v4 = textureLoad(source, vec2<i32>(fixed, clamp(first + j + 4, 0, last)), 0).rgb;
        let v5 = textureLoad(source, vec2<i32>(fixed, clamp(first + j + 5, 0, last)), 0).rgb;
        let v6 = textureLoad(source, vec2<i32>(fixed, clamp(first + j + 6, 0, last)), 0).rgb;
        let v7 = textureLoad(source, vec2<i32>(fixed, clamp(first + j + 7, 0, last)), 0).rgb;
        s0 += run_output(j, 0, v0, v1, v2, v3, v4, v5, v6, v7);
        s1 += run_output(j, 1, v0, v1, v2, v3, v4, v5, v6, v7);
        s2 += run_output(j, 2, v0, v1, v2, v3, v4, v5, v6, v7);
        s3 += run_output(j, 3, v0, v1, v2, v3, v4, v5, v6, v7);
        s4 += run_output(j, 4, v0, v1, v2, v3, v4, v5, v6, v7);
        s5 += run_output(j, 5, v0, v1, v2, v3, v4, v5, v6, v7);
        s6 += run_output(j, 6, v0, v1, v2, v3, v4, v5, v6, v7);
        s7 += run_output(j, 7, v0, v1, v2, v3, v4, v5, v6, v7);
    }
    // Stores written out: indexing a private array is slow on lavapipe.
    if (origin + 0 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 0), vec4<f32>(truncate8(s0 + SUM_EPSILON), 1.0));
    }
    if (origin + 1 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 1), vec4<f32>(truncate8(s1 + SUM_EPSILON), 1.0));
    }
    if (origin + 2 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 2), vec4<f32>(truncate8(s2 + SUM_EPSILON), 1.0));
    }
    if (origin + 3 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 3), vec4<f32>(truncate8(s3 + SUM_EPSILON), 1.0));
    }
    if (origin + 4 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 4), vec4<f32>(truncate8(s4 + SUM_EPSILON), 1.0));
    }
    if (origin + 5 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 5), vec4<f32>(truncate8(s5 + SUM_EPSILON), 1.0));
    }
    if (origin + 6 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 6), vec4<f32>(truncate8(s6 + SUM_EPSILON), 1.0));
    }
    if (origin + 7 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 7), vec4<f32>(truncate8(s7 + SUM_EPSILON), 1.0));
    }
}
