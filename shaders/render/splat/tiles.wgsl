// From projected Gaussians to per-tile lists: `depth_keys` keys each Gaussian by its depth (the
// float's bits, ordered like the depth; culled ones last) for the depth sort; `count_tiles` writes how many tiles each
// Gaussian (in depth order) touches, which is then scanned into its first instance slot;
// `duplicate` writes one (tile, Gaussian) instance per touched tile, and after the stable sort
// by tile `tile_ranges` marks where each tile's instances start and end.
#include "common/linear_group.wgsl"
#include "render/splat/types.wgsl"

@group(0) @binding(0) var<uniform> camera: SplatCamera;
@group(0) @binding(1) var<storage, read> splat_tiles: array<vec2<u32>>;
@group(0) @binding(2) var<storage, read> depth_order: array<u32>;
@group(0) @binding(3) var<storage, read_write> offsets: array<u32>;
@group(0) @binding(4) var<storage, read_write> instance_tiles: array<u32>;
@group(0) @binding(5) var<storage, read_write> instance_gaussians: array<u32>;
@group(0) @binding(6) var<storage, read_write> ranges: array<vec2<u32>>;

struct InstanceCount {
    n: u32,
}

@group(0) @binding(7) var<uniform> instances: InstanceCount;
@group(0) @binding(8) var<storage, read> splat_position: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read_write> keys: array<u32>;
@group(0) @binding(10) var<storage, read_write> order: array<u32>;

fn tile_count(tiles: vec2<u32>) -> u32 {
    let extent = tile_of(tiles.y) - tile_of(tiles.x);
    return extent.x * extent.y;
}

@compute @workgroup_size(256)
fn depth_keys(
    @builtin(local_invocation_index) t: u32,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let i = linear_group(group, groups) * 256u + t;
    if i >= camera.count {
        return;
    }
    order[i] = i;
    if tile_count(splat_tiles[i]) == 0u {
        keys[i] = 0xffffffffu;
    } else {
        keys[i] = bitcast<u32>(splat_position[i].z);
    }
}

@compute @workgroup_size(256)
fn count_tiles(
    @builtin(local_invocation_index) t: u32,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let j = linear_group(group, groups) * 256u + t;
    if j < camera.count {
        offsets[j] = tile_count(splat_tiles[depth_order[j]]);
    } else if j == camera.count {
        offsets[j] = 0u;
    }
}

@compute @workgroup_size(256)
fn duplicate(
    @builtin(local_invocation_index) t: u32,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let j = linear_group(group, groups) * 256u + t;
    if j >= camera.count {
        return;
    }
    let gaussian = depth_order[j];
    let tile_min = tile_of(splat_tiles[gaussian].x);
    let tile_max = tile_of(splat_tiles[gaussian].y);
    var at = offsets[j];
    for (var y = tile_min.y; y < tile_max.y; y++) {
        for (var x = tile_min.x; x < tile_max.x; x++) {
            instance_tiles[at] = y * camera.tiles.x + x;
            instance_gaussians[at] = gaussian;
            at++;
        }
    }
}

@compute @workgroup_size(256)
fn tile_ranges(
    @builtin(local_invocation_index) t: u32,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let i = linear_group(group, groups) * 256u + t;
    let n = instances.n;
    if i >= n {
        return;
    }
    let tile = instance_tiles[i];
    if i == 0u || instance_tiles[i - 1u] != tile {
        ranges[tile].x = i;
    }
    if i + 1u == n || instance_tiles[i + 1u] != tile {
        ranges[tile].y = i + 1u;
    }
}
