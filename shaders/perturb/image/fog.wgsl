// fog, final pass: x + amplitude * normalised plasma (the map's top-left H x W crop), rescaled by
// max / (max + amplitude) where max is the image's maximum (imagecorruptions `fog`).
#include "common/color.wgsl"
#include "perturb/image/pointwise_runs.wgsl"
#include "perturb/image/filter.wgsl"

struct Fog {
    amplitude: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> fog: Fog;
@group(0) @binding(3) var map: texture_2d<f32>;
@group(0) @binding(4) var<uniform> range: vec4<u32>;

fn unordered(u: u32) -> f32 {
    return bitcast<f32>(select(~u, u & 0x7fffffffu, (u & 0x80000000u) != 0u));
}

fn corrupt(p: vec2<u32>, x: vec3<f32>) -> vec3<f32> {
    let high = unordered(range[0]);
    let low = -unordered(range[1]);
    let brightest = unordered(range[2]);
    let plasma = (textureLoad(map, p, 0).x - low) / (high - low);
    let value = (x + fog.amplitude * plasma) * brightest / (brightest + fog.amplitude);
    return value + SUM_EPSILON;
}
