// vignetting: the cos⁴ law of natural vignetting in linear light, gain 1 / (1 + a·ρ²)² at radius
// ρ (1 at the corners) from the image centre; rounded to the nearest 8-bit level.
#include "common/color.wgsl"
#include "perturb/image/pointwise_runs.wgsl"

struct Params {
    key: vec4<u32>,
    // x: a = tan² of the half-diagonal field angle
    values: vec4<f32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Params;

fn corrupt(p: vec2<u32>, x: vec3<f32>) -> vec3<f32> {
    let centre = (vec2<f32>(textureDimensions(source)) - 1.0) * 0.5;
    let d = (vec2<f32>(p) - centre) / length(centre);
    let q = 1.0 + params.values.x * dot(d, d);
    return linear_to_srgb(srgb_to_linear(x) / (q * q)) + 0.5 / 255.0;
}
