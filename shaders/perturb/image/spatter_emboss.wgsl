// spatter (water), pass 14: the equalised distance through imagecorruptions' emboss kernel
// [[-2, -1, 0], [-1, 1, 1], [0, 1, 2]] (cv2.filter2D to 8 bits, BORDER_REFLECT_101).

@group(0) @binding(0) var distance: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;
@group(0) @binding(2) var<storage, read> lut: array<u32, 256>;

fn equalised(p: vec2<i32>, size: vec2<i32>) -> i32 {
    let q = (size - 1) - abs((size - 1) - abs(p));
    return i32(lut[u32(textureLoad(distance, q, 0).x)]);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(distance));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    let e = -2 * equalised(p + vec2<i32>(-1, -1), size) - equalised(p + vec2<i32>(0, -1), size)
        - equalised(p + vec2<i32>(-1, 0), size) + equalised(p, size) + equalised(p + vec2<i32>(1, 0), size)
        + equalised(p + vec2<i32>(0, 1), size) + 2 * equalised(p + vec2<i32>(1, 1), size);
    textureStore(output, p, vec4<f32>(f32(clamp(e, 0, 255)), 0.0, 0.0, 0.0));
}
