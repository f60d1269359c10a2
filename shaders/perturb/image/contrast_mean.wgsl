// contrast, pass 1: per-channel sums of the frame (r, g, b, pixel count) for the means.
#include "common/reduce.wgsl"

@group(0) @binding(0) var source: texture_2d<f32>;

@compute @workgroup_size(64)
fn partial_sums(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(source);
    if (id.x >= size.x) {
        return;
    }
    var acc = kahan_zero();
    for (var y = 0u; y < size.y; y++) {
        acc = kahan_add(acc, vec4<f32>(textureLoad(source, vec2<u32>(id.x, y), 0).rgb, 1.0));
    }
    store_column_sum(id.x, acc);
}
