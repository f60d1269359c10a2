// auto_exposure, pass 2: the frame's linear brightness for the controller, summed over the
// written 8-bit frame (r, g, b, pixel count).
#include "common/reduce.wgsl"
#include "common/color.wgsl"

@group(0) @binding(0) var source: texture_2d<f32>;

@compute @workgroup_size(64)
fn partial_sums(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(source);
    if (id.x >= size.x) {
        return;
    }
    var acc = kahan_zero();
    for (var y = 0u; y < size.y; y++) {
        let linear = srgb_to_linear(textureLoad(source, vec2<u32>(id.x, y), 0).rgb);
        acc = kahan_add(acc, vec4<f32>(linear, 1.0));
    }
    store_column_sum(id.x, acc);
}
