// depth_noise, pass 1: sums over the valid depth (z > 0) of (z, z², 1) for its standard deviation.
#include "common/reduce.wgsl"

@group(0) @binding(0) var depth: texture_2d<f32>;

@compute @workgroup_size(64)
fn partial_sums(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(depth);
    if (id.x >= size.x) {
        return;
    }
    var acc = kahan_zero();
    for (var y = 0u; y < size.y; y++) {
        let z = textureLoad(depth, vec2<u32>(id.x, y), 0).x;
        acc = kahan_add(acc, select(vec4<f32>(0.0), vec4<f32>(z, z * z, 1.0, 0.0), z > 0.0));
    }
    store_column_sum(id.x, acc);
}
