// snow, pass 1 of 3: the Gaussian noise N(mean, std) of imagecorruptions' snow layer at the grid
// cells its zoom reads, the centre crop and one cell past it (at the grid's edge the cell is
// clamped, as SciPy's zoom replicates it): one draw per cell, where reading the zoomed layer's
// four neighbours would draw each cell about 4 z^2 times.
#include "common/rng.wgsl"

struct Noise {
    key: vec4<u32>,
    // grid cell of noise cell (0, 0), noise grid size (the frame), noise cells written
    origin: vec2<u32>,
    grid: vec2<u32>,
    extent: vec2<u32>,
    mean: f32,
    deviation: f32,
}

@group(0) @binding(0) var cells: texture_storage_2d<r32float, write>;
@group(0) @binding(1) var<uniform> params: Noise;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.extent.x || id.y >= params.extent.y) {
        return;
    }
    let q = min(params.origin + id.xy, params.grid - 1u);
    let bits = rng_draw(params.key, vec4<u32>(q, 0u, 0u));
    let value = params.mean + params.deviation * rng_normal_pair(bits.x, bits.y).x;
    textureStore(cells, id.xy, vec4<f32>(value, 0.0, 0.0, 0.0));
}
