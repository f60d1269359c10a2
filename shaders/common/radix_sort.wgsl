// One pass of a stable LSD radix sort of (key, value) pairs on 4 bits of the key (driven by
// crates/gpu/src/radix_sort.rs): `count_digits` counts each block's digits into a digit-major
// histogram, which is then scanned (common/scan.wgsl) into each (digit, block)'s first output
// slot; `scatter` moves every pair there, after the block's earlier pairs of the same digit.
#include "common/linear_group.wgsl"

struct SortParams {
    n: u32,
    shift: u32,
    blocks: u32,
}

@group(0) @binding(0) var<uniform> params: SortParams;
@group(0) @binding(1) var<storage, read> keys_in: array<u32>;
@group(0) @binding(2) var<storage, read> values_in: array<u32>;
@group(0) @binding(3) var<storage, read_write> histogram: array<u32>;
@group(0) @binding(4) var<storage, read_write> keys_out: array<u32>;
@group(0) @binding(5) var<storage, read_write> values_out: array<u32>;

var<workgroup> digit_counts: array<atomic<u32>, 16>;
// Per digit an 8-bit counter, four digits a word: a block's earlier pairs of one digit number
// 255 at most, so a packed scan needs no carries.
var<workgroup> packed_counts: array<vec4<u32>, 256>;

fn digit_of(key: u32) -> u32 {
    return (key >> params.shift) & 15u;
}

@compute @workgroup_size(256)
fn count_digits(
    @builtin(local_invocation_index) t: u32,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let block = linear_group(group, groups);
    if t < 16u {
        atomicStore(&digit_counts[t], 0u);
    }
    workgroupBarrier();
    let i = block * 256u + t;
    if i < params.n {
        atomicAdd(&digit_counts[digit_of(keys_in[i])], 1u);
    }
    workgroupBarrier();
    if t < 16u {
        histogram[t * params.blocks + block] = atomicLoad(&digit_counts[t]);
    }
}

fn one_hot(digit: u32) -> vec4<u32> {
    var counter = vec4<u32>(0u);
    counter[digit >> 2u] = 1u << ((digit & 3u) * 8u);
    return counter;
}

@compute @workgroup_size(256)
fn scatter(
    @builtin(local_invocation_index) t: u32,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let block = linear_group(group, groups);
    let i = block * 256u + t;
    let valid = i < params.n;
    var key = 0u;
    var mine = vec4<u32>(0u);
    if valid {
        key = keys_in[i];
        mine = one_hot(digit_of(key));
    }
    packed_counts[t] = mine;
    for (var offset = 1u; offset < 256u; offset = offset << 1u) {
        workgroupBarrier();
        var sum = packed_counts[t];
        if t >= offset {
            sum += packed_counts[t - offset];
        }
        workgroupBarrier();
        packed_counts[t] = sum;
    }
    workgroupBarrier();
    if valid {
        let digit = digit_of(key);
        let before = packed_counts[t] - mine;
        let rank = (before[digit >> 2u] >> ((digit & 3u) * 8u)) & 255u;
        let at = histogram[digit * params.blocks + block] + rank;
        keys_out[at] = key;
        values_out[at] = values_in[i];
    }
}
