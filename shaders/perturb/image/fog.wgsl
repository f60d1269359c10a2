// fog, final pass: x + amplitude * normalised plasma (the map's top-left H x W crop), rescaled by
// max / (max + amplitude) where max is the image's maximum (imagecorruptions `fog`).
#include "common/color.wgsl"
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

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(source);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let high = unordered(range[0]);
    let low = -unordered(range[1]);
    let brightest = unordered(range[2]);
    let plasma = (textureLoad(map, id.xy, 0).x - low) / (high - low);
    let x = textureLoad(source, id.xy, 0).rgb + fog.amplitude * plasma;
    let value = x * brightest / (brightest + fog.amplitude);
    textureStore(output, id.xy, vec4<f32>(truncate8(value + SUM_EPSILON), 1.0));
}
