// The weighted sum of one output of a run of 8 (see Kernel1d in filter.wgsl): output o of the run
// takes the loop's source values v0..v7 at offset j with the weights from slot j + 8 - o on. The
// includer declares `kernel: Kernel1d` and `alias Value` (f32, vec2<f32> or vec3<f32>), the type
// of the values it filters.

fn run_output(j: i32, o: i32, v0: Value, v1: Value, v2: Value, v3: Value, v4: Value, v5: Value,
              v6: Value, v7: Value) -> Value {
    let t = j + 8 - o;
    return kernel.taps[t].x * v0 + kernel.taps[t + 1].x * v1
        + kernel.taps[t + 2].x * v2 + kernel.taps[t + 3].x * v3
        + kernel.taps[t + 4].x * v4 + kernel.taps[t + 5].x * v5
        + kernel.taps[t + 6].x * v6 + kernel.taps[t + 7].x * v7;
}
