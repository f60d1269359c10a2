// gaussian_blur, pass 1 of 2: the horizontal half of a separable Gaussian (SciPy
// gaussian_filter, mode 'nearest' = edge replicate) into an f32 scratch texture, in runs of 8
// pixels per invocation (see filter.wgsl). Also the first pass of glass_blur's blurs.
#include "perturb/image/filter.wgsl"
#include "perturb/image/kernel_run.wgsl"

alias Value = vec3<f32>;

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba32float, write>;
@group(0) @binding(2) var<uniform> kernel: Kernel1d;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let first = i32(id.x) * 8 - kernel.radius;
    let fixed = i32(id.y);
    let last = size.x - 1;
    let origin = i32(id.x) * 8;
    if (origin >= size.x || fixed >= size.y) {
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
        let v0 = textureLoad(source, vec2<i32>(clamp(first + j + 0, 0, last), fixed), 0).rgb;
        let v1 = textureLoad(source, vec2<i32>(clamp(first + j + 1, 0, last), fixed), 0).rgb;
        let v2 = textureLoad(source, vec2<i32>(clamp(first + j + 2, 0, last), fixed), 0).rgb;
        let v3 = textureLoad(source, vec2<i32>(clamp(first + j + 3, 0, last), fixed), 0).rgb;
        let v4 = textureLoad(source, vec2<i32>(clamp(first + j + 4, 0, last), fixed), 0).rgb;
        let v5 = textureLoad(source, vec2<i32>(clamp(first + j + 5, 0, last), fixed), 0).rgb;
        let v6 = textureLoad(source, vec2<i32>(clamp(first + j + 6, 0, last), fixed), 0).rgb;
        let v7 = textureLoad(source, vec2<i32>(clamp(first + j + 7, 0, last), fixed), 0).rgb;
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
    if (origin + 0 < size.x) {
        textureStore(output, vec2<i32>(origin + 0, fixed), vec4<f32>(s0, 1.0));
    }
    if (origin + 1 < size.x) {
        textureStore(output, vec2<i32>(origin + 1, fixed), vec4<f32>(s1, 1.0));
    }
    if (origin + 2 < size.x) {
        textureStore(output, vec2<i32>(origin + 2, fixed), vec4<f32>(s2, 1.0));
    }
    if (origin + 3 < size.x) {
        textureStore(output, vec2<i32>(origin + 3, fixed), vec4<f32>(s3, 1.0));
    }
    if (origin + 4 < size.x) {
        textureStore(output, vec2<i32>(origin + 4, fixed), vec4<f32>(s4, 1.0));
    }
    if (origin + 5 < size.x) {
        textureStore(output, vec2<i32>(origin + 5, fixed), vec4<f32>(s5, 1.0));
    }
    if (origin + 6 < size.x) {
        textureStore(output, vec2<i32>(origin + 6, fixed), vec4<f32>(s6, 1.0));
    }
    if (origin + 7 < size.x) {
        textureStore(output, vec2<i32>(origin + 7, fixed), vec4<f32>(s7, 1.0));
    }
}
