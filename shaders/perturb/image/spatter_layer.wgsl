// spatter's liquid layer: the blurred noise (filter_rows / filter_columns) with values below the
// threshold set to 0 (imagecorruptions' liquid_layer), read where it is used (water's Sobel and
// shade, the mud mask) rather than written out by a pass of its own. The includer binds
// `blurred` and `liquid`.

struct Liquid {
    threshold: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

fn liquid_layer(p: vec2<i32>) -> f32 {
    let v = textureLoad(blurred, p, 0).x;
    return select(v, 0.0, v < liquid.threshold);
}
