// spatter (water), pass 12: the distance through the equalisation table, once per pixel (the
// emboss pass reads each pixel seven times). The table is a uniform copy of the equalize pass's
// storage buffer, four entries per vec4: per-pixel storage-buffer reads are slow on lavapipe.

@group(0) @binding(0) var distance: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;
@group(0) @binding(2) var<uniform> lut: array<vec4<u32>, 64>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(distance);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let level = u32(textureLoad(distance, id.xy, 0).x);
    textureStore(output, id.xy, vec4<f32>(f32(lut[level >> 2u][level & 3u]), 0.0, 0.0, 0.0));
}
