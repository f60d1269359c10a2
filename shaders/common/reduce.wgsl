// Frame-wide sum of a vec4 (driven by crates/perturb/src/reduce.rs), without workgroup
// barriers (slow on CPU Vulkan). The including shader declares its input at binding 0 and an
// entry point `@compute @workgroup_size(64) fn partial_sums` that runs one invocation per column
// and stores that column's Kahan sum with `store_column_sum`; `finish_sums`, a single
// invocation, adds the column sums into `sums`.

@group(0) @binding(1) var<storage, read_write> partials: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> sums: vec4<f32>;

struct KahanSum {
    sum: vec4<f32>,
    carry: vec4<f32>,
}

fn kahan_add(acc: KahanSum, value: vec4<f32>) -> KahanSum {
    let y = value - acc.carry;
    let t = acc.sum + y;
    return KahanSum(t, (t - acc.sum) - y);
}

fn kahan_zero() -> KahanSum {
    return KahanSum(vec4<f32>(0.0), vec4<f32>(0.0));
}

fn store_column_sum(column: u32, acc: KahanSum) {
    partials[column] = acc.sum;
}

@compute @workgroup_size(1)
fn finish_sums() {
    var acc = kahan_zero();
    let count = arrayLength(&partials);
    for (var i = 0u; i < count; i++) {
        acc = kahan_add(acc, partials[i]);
    }
    sums = acc.sum;
}
