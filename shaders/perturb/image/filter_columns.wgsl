// A separable filter's vertical pass in runs of 8 pixels per invocation (see filter.wgsl). Edges
// and what the includer declares as filter_rows.wgsl.
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
    let first = i32(id.y) * 8 - kernel.radius;
    let fixed = i32(id.x);
    let origin = i32(id.y) * 8;
    if (fixed >= size.x || origin >= size.y) {
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
        let v0 = value(textureLoad(source, vec2<i32>(fixed, edge_index(first + j + 0, size.y)), 0));
        let v1 = value(textureLoad(source, vec2<i32>(fixed, edge_index(first + j + 1, size.y)), 0));
        let v2 = value(textureLoad(source, vec2<i32>(fixed, edge_index(first + j + 2, size.y)), 0));
        let v3 = value(textureLoad(source, vec2<i32>(fixed, edge_index(first + j + 3, size.y)), 0));
        let v4 = value(textureLoad(source, vec2<i32>(fixed, edge_index(first + j + 4, size.y)), 0));
        let v5 = value(textureLoad(source, vec2<i32>(fixed, edge_index(first + j + 5, size.y)), 0));
        let v6 = value(textureLoad(source, vec2<i32>(fixed, edge_index(first + j + 6, size.y)), 0));
        let v7 = value(textureLoad(source, vec2<i32>(fixed, edge_index(first + j + 7, size.y)), 0));
        s0 += run_output(j, 0, v0, v1, v2, v3, v4, v5, v6, v7);
        s1 += run_output(j, 1, v0, v1, v2, v3, v4, v5, v6, v7);
        s2 += run_output(j, 2, v0, v1, v2, v3, v4, v5, v6, v7);
        s3 += run_output(j, 3, v0, v1, v2, v3, v4, v5, v6, v7);
        s4 += run_output(j, 4, v0, v1, v2, v3, v4, v5, v6, v7);
        s5 += run_output(j, 5, v0, v1, v2, v3, v4, v5, v6, v7);
        s6 += run_output(j, 6, v0, v1, v2, v3, v4, v5, v6, v7);
        s7 += run_output(j, 7, v0, v1, v2, v3, v4, v5, v6, v7);
    }
    if (origin + 0 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 0), texel(s0));
    }
    if (origin + 1 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 1), texel(s1));
    }
    if (origin + 2 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 2), texel(s2));
    }
    if (origin + 3 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 3), texel(s3));
    }
    if (origin + 4 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 4), texel(s4));
    }
    if (origin + 5 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 5), texel(s5));
    }
    if (origin + 6 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 6), texel(s6));
    }
    if (origin + 7 < size.y) {
        textureStore(output, vec2<i32>(fixed, origin + 7), texel(s7));
    }
}
