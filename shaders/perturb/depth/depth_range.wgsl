// depth_range: depth outside [min, max] metres becomes invalid (0), in place.

struct Params {
    key: vec4<u32>,
    // x: min metres, y: max metres
    values: vec4<f32>,
}

@group(0) @binding(0) var depth: texture_storage_2d<r32float, read_write>;
@group(0) @binding(1) var<uniform> params: Params;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(depth);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let z = textureLoad(depth, id.xy).x;
    if (z < params.values.x || z > params.values.y) {
        textureStore(depth, id.xy, vec4<f32>(0.0));
    }
}
