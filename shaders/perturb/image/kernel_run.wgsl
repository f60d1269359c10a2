// The weighted sum of one output of a run of 8 (see Kernel1d in filter.wgsl): output o of the run
// takes the loop's source values v0..v7 at offset j with the weights from slot j + 8 - o on. The
// includer declares `kernel: Kernel1d`; one function per value width, as WGSL has no generics.

fn run_output3(j: i32, o: i32, v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, v3: vec3<f32>,
               v4: vec3<f32>, v5: vec3<f32>, v6: vec3<f32>, v7: vec3<f32>) -> vec3<f32> {
    let t = j + 8 - o;
    return kernel.taps[t].x * v0 + kernel.taps[t + 1].x * v1
        + kernel.taps[t + 2].x * v2 + kernel.taps[t + 3].x * v3
        + kernel.taps[t + 4].x * v4 + kernel.taps[t + 5].x * v5
        + kernel.taps[t + 6].x * v6 + kernel.taps[t + 7].x * v7;
}

fn run_output4(j: i32, o: i32, v0: vec4<f32>, v1: vec4<f32>, v2: vec4<f32>, v3: vec4<f32>,
               v4: vec4<f32>, v5: vec4<f32>, v6: vec4<f32>, v7: vec4<f32>) -> vec4<f32> {
    let t = j + 8 - o;
    return kernel.taps[t].x * v0 + kernel.taps[t + 1].x * v1
        + kernel.taps[t + 2].x * v2 + kernel.taps[t + 3].x * v3
        + kernel.taps[t + 4].x * v4 + kernel.taps[t + 5].x * v5
        + kernel.taps[t + 6].x * v6 + kernel.taps[t + 7].x * v7;
}
