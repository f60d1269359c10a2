// spatter (water), pass 14: the distance through the equalisation table, once per pixel (the
// emboss pass reads each pixel seven times; table reads from a storage buffer are slow on
// lavapipe).

@group(0) @binding(0) var distance: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;
@group(0) @binding(2) var<storage, read> lut: array<u32, 256>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(distance);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let level = u32(textureLoad(distance, id.xy, 0).x);
    textureStore(output, id.xy, vec4<f32>(f32(lut[level]), 0.0, 0.0, 0.0));
}
