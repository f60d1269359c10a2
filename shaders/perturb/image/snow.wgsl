// snow, pass 3 of 3: motion-blur the snow layer along the frame's angle (line taps, edges of the
// zoomed layer replicated), round it to 8 bits, lighten the image toward max(x, 1.5 gray + 0.5)
// by (1 - blend) and add the layer and the layer rotated by 180 degrees (imagecorruptions `snow`).
// Each invocation blurs the layer for a run of 8 pixels of a row and for the mirrored run of the
// mirrored row, and writes both runs: each pixel adds the one blur as its direct flakes and the
// other as its rotated ones, so every blur is computed once. The middle row of an odd height is
// its own mirror: there each invocation writes its own run only.
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

fn flake(x: i32, y: i32) -> f32 {
    return textureLoad(layer, vec2<i32>(clamp(x, 0, snow.zoomed.x - 1), y), 0).x;
}

fn composite(p: vec2<i32>, direct: f32, rotated: f32) {
    if (p.x < 0 || p.x >= i32(textureDimensions(source).x)) {
        return;
    }
    let x = textureLoad(source, p, 0).rgb;
    let gray = dot(x, vec3<f32>(0.299, 0.587, 0.114));
    let lightened = snow.blend * x + (1.0 - snow.blend) * max(x, vec3<f32>(gray * 1.5 + 0.5));
    let flakes = round(direct * 255.0) / 255.0 + round(rotated * 255.0) / 255.0;
    textureStore(output, p, vec4<f32>(truncate8(lightened + flakes), 1.0));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let x0 = i32(id.x) * 8;
    let y = i32(id.y);
    let mirrored_y = size.y - 1 - y;
    if (x0 >= size.x || y > mirrored_y) {
        return;
    }
    // Pixel (x0 + o, y) adds the layer at (x0 + o, y) and at (W - 1 - x0 - o, H - 1 - y).
    let mirrored_x = size.x - 1 - x0;
    var d0 = 0.0;
    var r0 = 0.0;
    var d1 = 0.0;
    var r1 = 0.0;
    var d2 = 0.0;
    var r2 = 0.0;
    var d3 = 0.0;
    var r3 = 0.0;
    var d4 = 0.0;
    var r4 = 0.0;
    var d5 = 0.0;
    var r5 = 0.0;
    var d6 = 0.0;
    var r6 = 0.0;
    var d7 = 0.0;
    var r7 = 0.0;
    for (var k = 0; k < line.count; k++) {
        let t = line.taps[k];
        let row = clamp(y + i32(t.y), 0, snow.zoomed.y - 1);
        let mirrored_row = clamp(mirrored_y + i32(t.y), 0, snow.zoomed.y - 1);
        let x = x0 + i32(t.x);
        let mx = mirrored_x + i32(t.x);
        d0 += t.z * flake(x + 0, row);
        r0 += t.z * flake(mx - 0, mirrored_row);
        d1 += t.z * flake(x + 1, row);
        r1 += t.z * flake(mx - 1, mirrored_row);
        d2 += t.z * flake(x + 2, row);
        r2 += t.z * flake(mx - 2, mirrored_row);
        d3 += t.z * flake(x + 3, row);
        r3 += t.z * flake(mx - 3, mirrored_row);
        d4 += t.z * flake(x + 4, row);
        r4 += t.z * flake(mx - 4, mirrored_row);
        d5 += t.z * flake(x + 5, row);
        r5 += t.z * flake(mx - 5, mirrored_row);
        d6 += t.z * flake(x + 6, row);
        r6 += t.z * flake(mx - 6, mirrored_row);
        d7 += t.z * flake(x + 7, row);
        r7 += t.z * flake(mx - 7, mirrored_row);
    }
    composite(vec2<i32>(x0 + 0, y), d0, r0);
    composite(vec2<i32>(x0 + 1, y), d1, r1);
    composite(vec2<i32>(x0 + 2, y), d2, r2);
    composite(vec2<i32>(x0 + 3, y), d3, r3);
    composite(vec2<i32>(x0 + 4, y), d4, r4);
    composite(vec2<i32>(x0 + 5, y), d5, r5);
    composite(vec2<i32>(x0 + 6, y), d6, r6);
    composite(vec2<i32>(x0 + 7, y), d7, r7);
    if (y == mirrored_y) {
        return;
    }
    composite(vec2<i32>(mirrored_x - 0, mirrored_y), r0, d0);
    composite(vec2<i32>(mirrored_x - 1, mirrored_y), r1, d1);
    composite(vec2<i32>(mirrored_x - 2, mirrored_y), r2, d2);
    composite(vec2<i32>(mirrored_x - 3, mirrored_y), r3, d3);
    composite(vec2<i32>(mirrored_x - 4, mirrored_y), r4, d4);
    composite(vec2<i32>(mirrored_x - 5, mirrored_y), r5, d5);
    composite(vec2<i32>(mirrored_x - 6, mirrored_y), r6, d6);
    composite(vec2<i32>(mirrored_x - 7, mirrored_y), r7, d7);
}
