// A separable filter's horizontal pass in runs of 8 pixels per invocation (see filter.wgsl): the
// Gaussians of gaussian_blur and glass_blur, the blur of spatter's noise and mud mask, and of
// elastic_transform's displacement fields. Edges: kernel.edge 0 = replicate, 1 = reflect (SciPy
// 'nearest' / 'reflect'). The includer declares the channels filtered (filter_r.wgsl,
// filter_rg.wgsl, filter_rgb.wgsl, filter_rgb8.wgsl): `alias Value`, `output` at binding 1, and
// `value` / `texel` between a texel and a Value.
#include "perturb/image/filter.wgsl"
#include "perturb/image/kernel_run.wgsl"

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(2) var<uniform> kernel: Kernel1d;

fn edge_index(i: i32, n: i32) -> i32 {
    let reflected = select(select(i, 2 * n - 1 - i, i >= n), -1 - i, i < 0);
    return clamp(select(i, reflected, kernel.edge == 1), 0, n - 1);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let first = i32(id.x) * 8 - kernel.radius;
    let fixed = i32(id.y);
    let origin = i32(id.x) * 8;
    if (origin >= size.x || fixed >= size.y) {
        return;
    }
    var s0 = Value(0.0);
    var s1 = Value(0.0);
    var s2 = Value(0.0);
    var s3 = Value(0.0);
    var s4 = Value(0.0);
    var s5 = Value(0.0);
    var s6 = Value(0.0);
    var s7 = Value(0.0);
    for (var j = 0; j < kernel.count; j += 8) {
        let v0 = value(textureLoad(source, vec2<i32>(edge_index(first + j + 0, size.x), fixed), 0));
        let v1 = value(textureLoad(source, vec2<i32>(edge_index(first + j + 1, size.x), fixed), 0));
        let v2 = value(textureLoad(source, vec2<i32>(edge_index(first + j + 2, size.x), fixed), 0));
        let v3 = value(textureLoad(source, vec2<i32>(edge_index(first + j + 3, size.x), fixed), 0));
        let v4 = value(textureLoad(source, vec2<i32>(edge_index(first + j + 4, size.x), fixed), 0));
        let v5 = value(textureLoad(source, vec2<i32>(edge_index(first + j + 5, size.x), fixed), 0));
        let v6 = value(textureLoad(source, vec2<i32>(edge_index(first + j + 6, size.x), fixed), 0));
        let v7 = value(textureLoad(source, vec2<i32>(edge_index(first + j + 7, size.x), fixed), 0));
        s0 += run_output(j, 0, v0, v1, v2, v3, v4, v5, v6, v7);
        s1 += run_output(j, 1, v0, v1, v2, v3, v4, v5, v6, v7);
        s2 += run_output(j, 2, v0, v1, v2, v3, v4, v5, v6, v7);
        s3 += run_output(j, 3, v0, v1, v2, v3, v4, v5, v6, v7);
        s4 += run_output(j, 4, v0, v1, v2, v3, v4, v5, v6, v7);
        s5 += run_output(j, 5, v0, v1, v2, v3, v4, v5, v6, v7);
        s6 += run_output(j, 6, v0, v1, v2, v3, v4, v5, v6, v7);
        s7 += run_output(j, 7, v0, v1, v2, v3, v4, v5, v6, v7);
    }
    if (origin + 0 < size.x) {
        textureStore(output, vec2<i32>(origin + 0, fixed), texel(s0));
    }
    if (origin + 1 < size.x) {
        textureStore(output, vec2<i32>(origin + 1, fixed), texel(s1));
    }
    if (origin + 2 < size.x) {
        textureStore(output, vec2<i32>(origin + 2, fixed), texel(s2));
    }
    if (origin + 3 < size.x) {
        textureStore(output, vec2<i32>(origin + 3, fixed), texel(s3));
    }
    if (origin + 4 < size.x) {
        textureStore(output, vec2<i32>(origin + 4, fixed), texel(s4));
    }
    if (origin + 5 < size.x) {
        textureStore(output, vec2<i32>(origin + 5, fixed), texel(s5));
    }
    if (origin + 6 < size.x) {
        textureStore(output, vec2<i32>(origin + 6, fixed), texel(s6));
    }
    if (origin + 7 < size.x) {
        textureStore(output, vec2<i32>(origin + 7, fixed), texel(s7));
    }
}
