// The entry point of the per-pixel corruptions (driven by PointwisePass) and of the last passes
// of contrast, fog, frost, elastic_transform and spatter: each invocation applies the includer's
// `fn corrupt(p, x) -> vec3<f32>` (x: the source pixel at p) to a run of 8 pixels of a row. The
// includer declares `source`, `output` and includes common/color.wgsl. On lavapipe this took the
// noises from 6.6 to 4.6 ms per 1200x680 frame; one pixel per invocation paid the invocation
// overhead.

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(source);
    let x0 = id.x * 8u;
    let y = id.y;
    if (x0 >= size.x || y >= size.y) {
        return;
    }
    corrupt_at(vec2<u32>(x0, y));
    if (x0 + 1u < size.x) { corrupt_at(vec2<u32>(x0 + 1u, y)); }
    if (x0 + 2u < size.x) { corrupt_at(vec2<u32>(x0 + 2u, y)); }
    if (x0 + 3u < size.x) { corrupt_at(vec2<u32>(x0 + 3u, y)); }
    if (x0 + 4u < size.x) { corrupt_at(vec2<u32>(x0 + 4u, y)); }
    if (x0 + 5u < size.x) { corrupt_at(vec2<u32>(x0 + 5u, y)); }
    if (x0 + 6u < size.x) { corrupt_at(vec2<u32>(x0 + 6u, y)); }
    if (x0 + 7u < size.x) { corrupt_at(vec2<u32>(x0 + 7u, y)); }
}

fn corrupt_at(p: vec2<u32>) {
    let x = textureLoad(source, p, 0).rgb;
    textureStore(output, p, vec4<f32>(truncate8(corrupt(p, x)), 1.0));
}
