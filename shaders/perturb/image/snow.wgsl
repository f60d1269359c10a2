// snow, pass 2 of 2: motion-blur the snow layer along the frame's angle (line taps, edges of the
// zoomed layer replicated), round it to 8 bits, lighten the image toward max(x, 1.5 gray + 0.5)
// by (1 - blend) and add the layer and the layer rotated by 180 degrees (imagecorruptions `snow`).
#include "common/color.wgsl"
#include "perturb/image/filter.wgsl"

struct Snow {
    // zoomed layer size
    zoomed: vec2<i32>,
    blend: f32,
    _pad: f32,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> snow: Snow;
@group(0) @binding(3) var layer: texture_2d<f32>;
@group(0) @binding(4) var<uniform> line: LineKernel;

fn tap(k: i32, p: vec2<i32>) -> f32 {
    let t = line.taps[k];
    let q = clamp(p + vec2<i32>(t.xy), vec2<i32>(0), snow.zoomed - 1);
    return t.z * textureLoad(layer, q, 0).x;
}

fn blurred(p: vec2<i32>) -> f32 {
    var sum = 0.0;
    for (var k = 0; k < line.count; k += 8) {
        sum += tap(k, p) + tap(k + 1, p) + tap(k + 2, p) + tap(k + 3, p);
        sum += tap(k + 4, p) + tap(k + 5, p) + tap(k + 6, p) + tap(k + 7, p);
    }
    return round(sum * 255.0) / 255.0;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    let x = textureLoad(source, p, 0).rgb;
    let gray = dot(x, vec3<f32>(0.299, 0.587, 0.114));
    let lightened = snow.blend * x + (1.0 - snow.blend) * max(x, vec3<f32>(gray * 1.5 + 0.5));
    let flakes = blurred(p) + blurred(size - 1 - p);
    textureStore(output, p, vec4<f32>(truncate8(lightened + flakes), 1.0));
}
