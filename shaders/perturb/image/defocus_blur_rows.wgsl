// defocus_blur, pass 1 of 2: running sums along each row, the image extended by the kernel
// radius with OpenCV's BORDER_REFLECT_101: P[y][j] = sum over t < j of (I[y][t - R] - 1/2).
// Centring the values on 0 keeps the f32 sums small, so box sums taken as differences stay exact
// to ~1e-6. One invocation per row.

struct Prefix {
    radius: i32,
    _pad0: i32,
    _pad1: i32,
    _pad2: i32,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var prefix: texture_storage_2d<rgba32float, write>;
@group(0) @binding(2) var<uniform> params: Prefix;

fn reflect101(i: i32, n: i32) -> i32 {
    return (n - 1) - abs((n - 1) - abs(i));
}

@compute @workgroup_size(64, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let y = i32(id.x);
    if (y >= size.y) {
        return;
    }
    let extended = size.x + 2 * params.radius;
    var sum = vec3<f32>(0.0);
    textureStore(prefix, vec2<i32>(0, y), vec4<f32>(sum, 0.0));
    for (var j = 0; j < extended; j++) {
        let x = reflect101(j - params.radius, size.x);
        sum += textureLoad(source, vec2<i32>(x, y), 0).rgb - 0.5;
        textureStore(prefix, vec2<i32>(j + 1, y), vec4<f32>(sum, 0.0));
    }
}
