// Exclusive prefix sum of u32 in place, 256 values a workgroup (driven by
// crates/gpu/src/scan.rs): `scan_blocks` scans each block and stores its total, the totals are
// scanned the same way, and `add_block_sums` adds each block's scanned total back.
#include "common/linear_group.wgsl"

struct ScanParams {
    n: u32,
}

@group(0) @binding(0) var<uniform> params: ScanParams;
@group(0) @binding(1) var<storage, read_write> data: array<u32>;
@group(0) @binding(2) var<storage, read_write> block_sums: array<u32>;

var<workgroup> partial: array<u32, 256>;

@compute @workgroup_size(256)
fn scan_blocks(
    @builtin(local_invocation_index) t: u32,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let block = linear_group(group, groups);
    let i = block * 256u + t;
    var value = 0u;
    if i < params.n {
        value = data[i];
    }
    partial[t] = value;
    for (var offset = 1u; offset < 256u; offset = offset << 1u) {
        workgroupBarrier();
        var sum = partial[t];
        if t >= offset {
            sum += partial[t - offset];
        }
        workgroupBarrier();
        partial[t] = sum;
    }
    workgroupBarrier();
    if i < params.n {
        data[i] = partial[t] - value;
    }
    if t == 255u {
        block_sums[block] = partial[255];
    }
}

@compute @workgroup_size(256)
fn add_block_sums(
    @builtin(local_invocation_index) t: u32,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let block = linear_group(group, groups);
    let i = block * 256u + t;
    if i < params.n {
        data[i] += block_sums[block];
    }
}
