// spatter (water), pass 13: 3x3 box mean of the embossed distance (cv2.blur on 8 bits: rounded,
// BORDER_REFLECT_101) times the 8-bit liquid layer; the maximum goes to an atomic (the values are
// non-negative, so their f32 bits order like the values).

@group(0) @binding(0) var embossed: texture_2d<f32>;
@group(0) @binding(1) var liquid_layer: texture_2d<f32>;
@group(0) @binding(2) var output: texture_storage_2d<r32float, write>;
@group(0) @binding(3) var<storage, read_write> maximum: array<atomic<u32>, 4>;

fn embossed_at(p: vec2<i32>, size: vec2<i32>) -> f32 {
    let q = (size - 1) - abs((size - 1) - abs(p));
    return textureLoad(embossed, q, 0).x;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(embossed));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    // The 3x3 neighbourhood written out (loops are slow on lavapipe), in row order.
    var sum = 0.0;
    sum += embossed_at(p + vec2<i32>(-1, -1), size);
    sum += embossed_at(p + vec2<i32>(0, -1), size);
    sum += embossed_at(p + vec2<i32>(1, -1), size);
    sum += embossed_at(p + vec2<i32>(-1, 0), size);
    sum += embossed_at(p + vec2<i32>(0, 0), size);
    sum += embossed_at(p + vec2<i32>(1, 0), size);
    sum += embossed_at(p + vec2<i32>(-1, 1), size);
    sum += embossed_at(p + vec2<i32>(0, 1), size);
    sum += embossed_at(p + vec2<i32>(1, 1), size);
    let shade = round(sum / 9.0);
    let liquid = floor(textureLoad(liquid_layer, p, 0).x * 255.0);
    let m = liquid * shade;
    atomicMax(&maximum[0], bitcast<u32>(m));
    textureStore(output, p, vec4<f32>(m, 0.0, 0.0, 0.0));
}
