// spatter, pass 4: the blurred noise (filter_rows / filter_columns) with values below the
// threshold set to 0: imagecorruptions' liquid layer; or, for mud, the mask liquid > threshold.

struct Liquid {
    threshold: f32,
    // 0: write the liquid layer, 1: the mud mask
    mask: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var blurred: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;
@group(0) @binding(2) var<uniform> liquid: Liquid;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(blurred);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let v = textureLoad(blurred, id.xy, 0).x;
    let layer = select(v, 0.0, v < liquid.threshold);
    let mask = select(0.0, 1.0, layer > liquid.threshold);
    let value = select(layer, mask, liquid.mask == 1u);
    textureStore(output, id.xy, vec4<f32>(value, 0.0, 0.0, 0.0));
}
