// snow, pass 2 of 3: imagecorruptions' snow layer before its motion blur: the noise of pass 1
// `clipped_zoom`ed (centre crop scaled up by SciPy zoom(order=1), corner-aligned), values below
// the threshold set to 0, clipped to [0, 1]. Written for the whole zoomed size round(crop * z),
// which is at least H x W (the blur sees its edges).

struct Layer {
    // (top x, top y, scale x, scale y) of the zoom
    window: vec4<f32>,
    // zoomed layer size, grid cell of noise cell (0, 0)
    zoomed: vec2<u32>,
    origin: vec2<i32>,
    threshold: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

@group(0) @binding(0) var layer: texture_storage_2d<r32float, write>;
@group(0) @binding(1) var<uniform> params: Layer;
@group(0) @binding(2) var cells: texture_2d<f32>;

fn noise(q: vec2<i32>) -> f32 {
    return textureLoad(cells, q - params.origin, 0).x;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.zoomed.x || id.y >= params.zoomed.y) {
        return;
    }
    let at = params.window.xy + vec2<f32>(id.xy) * params.window.zw;
    let base = floor(at);
    let f = at - base;
    let q = vec2<i32>(base);
    let upper = mix(noise(q), noise(q + vec2<i32>(1, 0)), f.x);
    let lower = mix(noise(q + vec2<i32>(0, 1)), noise(q + vec2<i32>(1, 1)), f.x);
    var v = mix(upper, lower, f.y);
    if (v < params.threshold) {
        v = 0.0;
    }
    textureStore(layer, id.xy, vec4<f32>(clamp(v, 0.0, 1.0), 0.0, 0.0, 0.0));
}
