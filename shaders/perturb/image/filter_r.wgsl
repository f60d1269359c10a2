// One channel for filter_rows.wgsl / filter_columns.wgsl: spatter's noise and mud mask.

alias Value = f32;

@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;

fn value(t: vec4<f32>) -> Value {
    return t.x;
}

fn texel(v: Value) -> vec4<f32> {
    return vec4<f32>(v, 0.0, 0.0, 0.0);
}
