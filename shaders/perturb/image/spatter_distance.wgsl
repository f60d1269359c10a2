// spatter (water), pass 12: distance to the nearest edge truncated at 20 (cv2.threshold TRUNC),
// 3x3 box mean (cv2.blur, BORDER_REFLECT_101), truncated to 8 bits; counted into a histogram
// for equalizeHist.

@group(0) @binding(0) var seeds: texture_2d<u32>;
@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;
@group(0) @binding(2) var<storage, read_write> histogram: array<atomic<u32>, 256>;

const NONE: u32 = 0xffffffffu;
const TRUNCATE: f32 = 20.0;

fn reflect101(p: vec2<i32>, size: vec2<i32>) -> vec2<i32> {
    return (size - 1) - abs((size - 1) - abs(p));
}

fn distance_at(p: vec2<i32>, size: vec2<i32>) -> f32 {
    let q = reflect101(p, size);
    let seed = textureLoad(seeds, q, 0).x;
    if (seed == NONE) {
        return TRUNCATE;
    }
    let s = vec2<i32>(i32(seed & 0xffffu), i32(seed >> 16u));
    return min(length(vec2<f32>(s - q)), TRUNCATE);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(seeds));
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
