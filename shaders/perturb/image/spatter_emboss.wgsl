// spatter (water), pass 12: the equalised distance through imagecorruptions' emboss kernel
// [[-2, -1, 0], [-1, 1, 1], [0, 1, 2]] (cv2.filter2D to 8 bits, BORDER_REFLECT_101).

@group(0) @binding(0) var equalised: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;

fn at(p: vec2<i32>, size: vec2<i32>) -> f32 {
    let q = (size - 1) - abs((size - 1) - abs(p));
    return textureLoad(equalised, q, 0).x;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(equalised));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    let e = -2.0 * at(p + vec2<i32>(-1, -1), size) - at(p + vec2<i32>(0, -1), size)
        - at(p + vec2<i32>(-1, 0), size) + at(p, size) + at(p + vec2<i32>(1, 0), size)
        + at(p + vec2<i32>(0, 1), size) + 2.0 * at(p + vec2<i32>(1, 1), size);
    textureStore(output, p, vec4<f32>(clamp(e, 0.0, 255.0), 0.0, 0.0, 0.0));
}
