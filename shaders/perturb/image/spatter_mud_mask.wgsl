// spatter (mud), pass 4: the mud mask, 1 where the liquid layer exceeds the threshold, for the
// mask blur (filter_rows / filter_columns) and spatter_mud.wgsl.
#include "perturb/image/spatter_layer.wgsl"

@group(0) @binding(0) var blurred: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;
@group(0) @binding(2) var<uniform> liquid: Liquid;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(blurred);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let mask = select(0.0, 1.0, liquid_layer(vec2<i32>(id.xy)) > liquid.threshold);
    textureStore(output, id.xy, vec4<f32>(mask, 0.0, 0.0, 0.0));
}
