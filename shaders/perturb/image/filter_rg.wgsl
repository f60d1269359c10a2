// Two channels for filter_rows.wgsl / filter_columns.wgsl: elastic_transform's x and y
// displacement fields.

alias Value = vec2<f32>;

@group(0) @binding(1) var output: texture_storage_2d<rg32float, write>;

fn value(t: vec4<f32>) -> Value {
    return t.xy;
}

fn texel(v: Value) -> vec4<f32> {
    return vec4<f32>(v, 0.0, 0.0);
}
