// contrast, pass 2: (x - mean) * c + mean with the per-channel means of the frame
// (imagecorruptions `contrast`).
#include "common/color.wgsl"

struct Params {
    key: vec4<u32>,
    // x: factor c
    values: vec4<f32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Params;
// (sum r, sum g, sum b, pixel count) from contrast_mean.wgsl
@group(0) @binding(3) var<uniform> sums: vec4<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(source);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let mean = sums.rgb / sums.w;
    let x = textureLoad(source, id.xy, 0).rgb;
    textureStore(output, id.xy, vec4<f32>(truncate8((x - mean) * params.values.x + mean), 1.0));
}
