// shot_noise: Poisson(x·c) / c per pixel and channel, c photons at full scale (imagecorruptions
// `shot_noise`). The Poisson sampler is exact at every rate (see common/rng.wgsl).
#include "common/rng.wgsl"
#include "common/color.wgsl"

struct Params {
    key: vec4<u32>,
    // x: photons c
    values: vec4<f32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Params;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(source);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let x = textureLoad(source, id.xy, 0).rgb;
    let c = params.values.x;
    var y: vec3<f32>;
    for (var channel = 0u; channel < 3u; channel++) {
        y[channel] = rng_poisson(params.key, vec3<u32>(id.x, id.y, channel), x[channel] * c) / c;
    }
    textureStore(output, id.xy, vec4<f32>(truncate8(y), 1.0));
}
