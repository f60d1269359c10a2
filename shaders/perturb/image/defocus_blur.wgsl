// defocus_blur, pass 2 of 2: imagecorruptions' anti-aliased disk kernel (OpenCV filter2D,
// BORDER_REFLECT_101) applied exactly, as a sum of centred row boxes [-k, k] with weights a, each
// box one difference of the running sums of pass 1: one box per disk row over the blurred
// image's sums, then the kernel's correction boxes over the plain image's sums (the rows from
// row h on). Boxes are built on the CPU from the kernel. Each invocation writes a run of 8
// pixels of a row (one box parameter read per 8 outputs; see filter.wgsl).
#include "common/color.wgsl"
#include "perturb/image/filter.wgsl"

struct Boxes {
    radius: i32,
    // number of boxes
    count: i32,
    // 1/2 x the kernel's sum: the running sums are of (I - 1/2).
    offset: f32,
    _pad: f32,
    // (row offset dy, half width k, weight a, first prefix row: 0 blurred, h plain)
    boxes: array<vec4<f32>, 128>,
}

@group(0) @binding(0) var prefix: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Boxes;

fn reflect101(i: i32, n: i32) -> i32 {
    return (n - 1) - abs((n - 1) - abs(i));
}

fn box_sum(y: i32, right: i32, left: i32) -> vec3<f32> {
    return textureLoad(prefix, vec2<i32>(right, y), 0).rgb - textureLoad(prefix, vec2<i32>(left, y), 0).rgb;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(output));
    let x0 = i32(id.x) * 8;
    let y = i32(id.y);
    if (x0 >= size.x || y >= size.y) {
        return;
    }
    // Prefix columns past the image's right edge exist (the texture is wider), so runs that
    // overhang the image read valid memory; their outputs are not stored.
    var s0 = vec3<f32>(params.offset);
    var s1 = vec3<f32>(params.offset);
    var s2 = vec3<f32>(params.offset);
    var s3 = vec3<f32>(params.offset);
    var s4 = vec3<f32>(params.offset);
    var s5 = vec3<f32>(params.offset);
    var s6 = vec3<f32>(params.offset);
    var s7 = vec3<f32>(params.offset);
    for (var b = 0; b < params.count; b++) {
        let box = params.boxes[b];
        let row = i32(box.w) + reflect101(y + i32(box.x), size.y);
        let k = i32(box.y);
        // Columns x-k..=x+k of the image are prefix columns x-k+R+1 ..= x+k+R+1.
        let right = x0 + k + params.radius + 1;
        let left = x0 - k + params.radius;
        s0 += box.z * box_sum(row, right + 0, left + 0);
        s1 += box.z * box_sum(row, right + 1, left + 1);
        s2 += box.z * box_sum(row, right + 2, left + 2);
        s3 += box.z * box_sum(row, right + 3, left + 3);
        s4 += box.z * box_sum(row, right + 4, left + 4);
        s5 += box.z * box_sum(row, right + 5, left + 5);
        s6 += box.z * box_sum(row, right + 6, left + 6);
        s7 += box.z * box_sum(row, right + 7, left + 7);
    }
    if (x0 + 0 < size.x) {
        textureStore(output, vec2<i32>(x0 + 0, y), vec4<f32>(truncate8(s0 + SUM_EPSILON), 1.0));
    }
    if (x0 + 1 < size.x) {
        textureStore(output, vec2<i32>(x0 + 1, y), vec4<f32>(truncate8(s1 + SUM_EPSILON), 1.0));
    }
    if (x0 + 2 < size.x) {
        textureStore(output, vec2<i32>(x0 + 2, y), vec4<f32>(truncate8(s2 + SUM_EPSILON), 1.0));
    }
    if (x0 + 3 < size.x) {
        textureStore(output, vec2<i32>(x0 + 3, y), vec4<f32>(truncate8(s3 + SUM_EPSILON), 1.0));
    }
    if (x0 + 4 < size.x) {
        textureStore(output, vec2<i32>(x0 + 4, y), vec4<f32>(truncate8(s4 + SUM_EPSILON), 1.0));
    }
    if (x0 + 5 < size.x) {
        textureStore(output, vec2<i32>(x0 + 5, y), vec4<f32>(truncate8(s5 + SUM_EPSILON), 1.0));
    }
    if (x0 + 6 < size.x) {
        textureStore(output, vec2<i32>(x0 + 6, y), vec4<f32>(truncate8(s6 + SUM_EPSILON), 1.0));
    }
    if (x0 + 7 < size.x) {
        textureStore(output, vec2<i32>(x0 + 7, y), vec4<f32>(truncate8(s7 + SUM_EPSILON), 1.0));
    }
}
