// defocus_blur, pass 1 of 2: running sums along each row of the image extended by the kernel
// radius R with OpenCV's BORDER_REFLECT_101, of the image blurred by the small anti-alias
// Gaussian (rows 0..h of the prefix texture) and of the plain image (rows h..2h):
// P[y][j] = sum over t < j of (I[y][t - R] - 1/2). Centring the values on 0 keeps the f32 sums
// small, so box sums taken as differences stay exact to ~1e-6. The blur is separable and
// symmetric, so blurring the extended row equals extending the blurred row: each step blurs one
// new column vertically and the horizontal taps slide over the last five columns. One
// invocation per row.

struct Prefix {
    radius: i32,
    _pad0: i32,
    _pad1: i32,
    _pad2: i32,
    // weights at offsets -2..=2 in .x (3-tap kernels padded with zeros)
    gauss: array<vec4<f32>, 5>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var prefix: texture_storage_2d<rgba32float, write>;
@group(0) @binding(2) var<uniform> params: Prefix;

var<private> size: vec2<i32>;
var<private> rows: array<i32, 5>;

fn reflect101(i: i32, n: i32) -> i32 {
    return (n - 1) - abs((n - 1) - abs(i));
}

fn centred(x: i32, y: i32) -> vec3<f32> {
    return textureLoad(source, vec2<i32>(x, y), 0).rgb - 0.5;
}

// Column j of the extended row, blurred vertically.
fn column(j: i32) -> vec3<f32> {
    let x = reflect101(j - params.radius, size.x);
    var sum = params.gauss[0].x * centred(x, rows[0]);
    sum += params.gauss[1].x * centred(x, rows[1]);
    sum += params.gauss[2].x * centred(x, rows[2]);
    sum += params.gauss[3].x * centred(x, rows[3]);
    sum += params.gauss[4].x * centred(x, rows[4]);
    return sum;
}

@compute @workgroup_size(64, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    size = vec2<i32>(textureDimensions(source));
    let y = i32(id.x);
    if (y >= size.y) {
        return;
    }
    for (var t = 0; t < 5; t++) {
        rows[t] = reflect101(y + t - 2, size.y);
    }
    let extended = size.x + 2 * params.radius;
    var blurred_sum = vec3<f32>(0.0);
    var plain_sum = vec3<f32>(0.0);
    textureStore(prefix, vec2<i32>(0, y), vec4<f32>(0.0));
    textureStore(prefix, vec2<i32>(0, y + size.y), vec4<f32>(0.0));
    // c0..c4: the vertically blurred columns j-2..j+2.
    var c0 = column(-2);
    var c1 = column(-1);
    var c2 = column(0);
    var c3 = column(1);
    for (var j = 0; j < extended; j++) {
        let c4 = column(j + 2);
        var blurred = params.gauss[0].x * c0;
        blurred += params.gauss[1].x * c1;
        blurred += params.gauss[2].x * c2;
        blurred += params.gauss[3].x * c3;
        blurred += params.gauss[4].x * c4;
        blurred_sum += blurred;
        plain_sum += centred(reflect101(j - params.radius, size.x), y);
        textureStore(prefix, vec2<i32>(j + 1, y), vec4<f32>(blurred_sum, 0.0));
        textureStore(prefix, vec2<i32>(j + 1, y + size.y), vec4<f32>(plain_sum, 0.0));
        c0 = c1;
        c1 = c2;
        c2 = c3;
        c3 = c4;
    }
}
