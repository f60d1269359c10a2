// fog, reduction: the plasma map's minimum and maximum (imagecorruptions normalises the whole
// map to [0, 1]) and the image's maximum over all channels (the fog is rescaled by
// max / (max + amplitude)). Each invocation covers 16 texels of a row; results go through
// atomics on order-preserving integer encodings of the floats.

@group(0) @binding(0) var map: texture_2d<f32>;
@group(0) @binding(1) var image: texture_2d<f32>;
// [0]: encoded map maximum, [1]: encoded negated map minimum, [2]: encoded image maximum;
// cleared to 0 before the pass.
@group(0) @binding(2) var<storage, read_write> range: array<atomic<u32>, 4>;

// Monotonic f32 -> u32: larger floats map to larger integers.
fn ordered(v: f32) -> u32 {
    let bits = bitcast<u32>(v);
    return select(bits | 0x80000000u, ~bits, (bits & 0x80000000u) != 0u);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(map);
    let x0 = id.x * 16u;
    if (x0 >= size.x || id.y >= size.y) {
        return;
    }
    var high = -3.4e38;
    var low = 3.4e38;
    for (var i = 0u; i < 16u; i++) {
        let v = textureLoad(map, vec2<u32>(x0 + i, id.y), 0).x;
        high = max(high, v);
        low = min(low, v);
    }
    atomicMax(&range[0], ordered(high));
    atomicMax(&range[1], ordered(-low));
    let image_size = textureDimensions(image);
    if (id.y < image_size.y && x0 < image_size.x) {
        var brightest = 0.0;
        for (var i = 0u; i < 16u; i++) {
            let x = min(x0 + i, image_size.x - 1u);
            let c = textureLoad(image, vec2<u32>(x, id.y), 0).rgb;
            brightest = max(brightest, max(c.r, max(c.g, c.b)));
        }
        atomicMax(&range[2], ordered(brightest));
    }
}
