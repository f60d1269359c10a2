// spatter (water), pass 13: the equalised distance through imagecorruptions' emboss kernel
// [[-2, -1, 0], [-1, 1, 1], [0, 1, 2]] (cv2.filter2D to 8 bits, BORDER_REFLECT_101).
#include "perturb/image/window_runs.wgsl"

@group(0) @binding(0) var equalised: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;

fn frame_size() -> vec2<i32> {
    return vec2<i32>(textureDimensions(equalised));
}

fn sample(p: vec2<i32>) -> f32 {
    let size = frame_size();
    return textureLoad(equalised, (size - 1) - abs((size - 1) - abs(p)), 0).x;
}

fn pixel(p: vec2<i32>, w: Window) {
    let e = -2.0 * w.l.x - w.c.x - w.l.y + w.c.y + w.r.y + w.c.z + 2.0 * w.r.z;
    textureStore(output, p, vec4<f32>(clamp(e, 0.0, 255.0), 0.0, 0.0, 0.0));
}
