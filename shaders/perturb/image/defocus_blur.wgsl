// defocus_blur, pass 2 of 2: imagecorruptions' anti-aliased disk kernel (OpenCV filter2D,
// BORDER_REFLECT_101) applied exactly, as a sum of centred row boxes: every kernel row is
// symmetric, so it is a sum of boxes [-k, k] with weights a, each box one difference of the
// running sums of pass 1. Boxes are built on the CPU from the kernel.
#include "common/color.wgsl"
#include "perturb/image/filter.wgsl"

struct Boxes {
    radius: i32,
    // a multiple of 8, padded with zero-weight boxes
    count: i32,
    // 1/2 x the kernel's sum: the running sums are of (I - 1/2).
    offset: f32,
    _pad: f32,
    // (row offset dy, half width k, weight a, 0)
    boxes: array<vec4<f32>, 128>,
}

@group(0) @binding(0) var prefix: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Boxes;

fn reflect101(i: i32, n: i32) -> i32 {
    return (n - 1) - abs((n - 1) - abs(i));
}

fn box_sum(b: i32, p: vec2<i32>, height: i32) -> vec3<f32> {
    let box = params.boxes[b];
    let y = reflect101(p.y + i32(box.x), height);
    let k = i32(box.y);
    // Columns x-k..=x+k of the image are prefix columns x-k+R+1 ..= x+k+R+1.
    let right = textureLoad(prefix, vec2<i32>(p.x + k + params.radius + 1, y), 0).rgb;
    let left = textureLoad(prefix, vec2<i32>(p.x - k + params.radius, y), 0).rgb;
    return box.z * (right - left);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(output));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    var sum = vec3<f32>(params.offset);
    for (var b = 0; b < params.count; b += 8) {
        sum += box_sum(b, p, size.y) + box_sum(b + 1, p, size.y);
        sum += box_sum(b + 2, p, size.y) + box_sum(b + 3, p, size.y);
        sum += box_sum(b + 4, p, size.y) + box_sum(b + 5, p, size.y);
        sum += box_sum(b + 6, p, size.y) + box_sum(b + 7, p, size.y);
    }
    textureStore(output, p, vec4<f32>(truncate8(sum + SUM_EPSILON), 1.0));
}
