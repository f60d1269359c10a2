// spatter (water), pass 9: distance to the nearest edge truncated at 20 (cv2.threshold TRUNC),
// from the squared distances of spatter_squared_distance.wgsl; 3x3 box mean (cv2.blur,
// BORDER_REFLECT_101), truncated to 8 bits; counted into a histogram for equalizeHist.

@group(0) @binding(0) var squared: texture_2d<u32>;
@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;
@group(0) @binding(2) var<storage, read_write> histogram: array<atomic<u32>, 256>;

// TRUNCATE^2
const TRUNCATE_SQUARED: u32 = 400u;

fn reflect101(p: vec2<i32>, size: vec2<i32>) -> vec2<i32> {
    return (size - 1) - abs((size - 1) - abs(p));
}

fn distance_at(p: vec2<i32>, size: vec2<i32>) -> f32 {
    let d2 = textureLoad(squared, reflect101(p, size), 0).x;
    return sqrt(f32(min(d2, TRUNCATE_SQUARED)));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(squared));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    // The 3x3 neighbourhood written out (loops are slow on lavapipe), in row order.
    var sum = 0.0;
    sum += distance_at(p + vec2<i32>(-1, -1), size);
    sum += distance_at(p + vec2<i32>(0, -1), size);
    sum += distance_at(p + vec2<i32>(1, -1), size);
    sum += distance_at(p + vec2<i32>(-1, 0), size);
    sum += distance_at(p + vec2<i32>(0, 0), size);
    sum += distance_at(p + vec2<i32>(1, 0), size);
    sum += distance_at(p + vec2<i32>(-1, 1), size);
    sum += distance_at(p + vec2<i32>(0, 1), size);
    sum += distance_at(p + vec2<i32>(1, 1), size);
    let value = floor(sum / 9.0);
    atomicAdd(&histogram[u32(value)], 1u);
    textureStore(output, p, vec4<f32>(value, 0.0, 0.0, 0.0));
}
