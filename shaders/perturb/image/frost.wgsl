// frost, per frame: a * x + b * F with the frost texture F cropped at the frame's offset
// (imagecorruptions `frost` blends a randomly cropped frost photo the same way).
#include "common/color.wgsl"

struct Frost {
    offset: vec2<i32>,
    image_weight: f32,
    frost_weight: f32,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> frost: Frost;
@group(0) @binding(3) var ice: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    let x = textureLoad(source, p, 0).rgb;
    let f = textureLoad(ice, p + frost.offset, 0).rgb;
    textureStore(output, p, vec4<f32>(truncate8(frost.image_weight * x + frost.frost_weight * f), 1.0));
}
