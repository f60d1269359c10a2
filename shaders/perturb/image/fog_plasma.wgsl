// fog, passes 1..2L: the plasma fractal of imagecorruptions' `plasma_fractal` (diamond-square on a
// wrapping N x N map, N a power of two >= max(H, W)), one level per dispatch pair. Each new point
// is the mean of its four neighbours plus wibble * U(-wibble, wibble); wibble shrinks by the
// decay after every level. The point (0, 0) is 0.
#include "common/rng.wgsl"

struct Level {
    key: vec4<u32>,
    // distance between the points that already exist at this level
    step: u32,
    size: u32,
    wibble: f32,
    _pad: f32,
}

@group(0) @binding(0) var map: texture_storage_2d<r32float, read_write>;
@group(0) @binding(1) var<uniform> level: Level;

fn at(x: u32, y: u32) -> f32 {
    let mask = level.size - 1u;
    return textureLoad(map, vec2<u32>(x & mask, y & mask)).x;
}

fn wibbled_mean(sum: f32, x: u32, y: u32) -> f32 {
    let u = rng_uniform(rng_draw(level.key, vec4<u32>(x, y, 0u, 0u)).x);
    return sum / 4.0 + level.wibble * ((2.0 * u - 1.0) * level.wibble);
}

// The centre of every square of existing points.
@compute @workgroup_size(8, 8)
fn square(@builtin(global_invocation_id) id: vec3<u32>) {
    let cells = level.size / level.step;
    if (id.x >= cells || id.y >= cells) {
        return;
    }
    let s = level.step;
    let x = id.x * s;
    let y = id.y * s;
    var sum = 0.0;
    if (s == level.size) {
        // First level: all four corners are the point (0, 0), which is 0.
        textureStore(map, vec2<u32>(0u, 0u), vec4<f32>(0.0));
    } else {
        sum = (at(x, y) + at(x, y + s)) + (at(x + s, y) + at(x + s, y + s));
    }
    let c = vec2<u32>(x + s / 2u, y + s / 2u);
    textureStore(map, c, vec4<f32>(wibbled_mean(sum, c.x, c.y), 0.0, 0.0, 0.0));
}

// The midpoints of the edges between existing points: each invocation fills the one right of
// its corner and the one below it.
@compute @workgroup_size(8, 8)
fn diamond(@builtin(global_invocation_id) id: vec3<u32>) {
    let cells = level.size / level.step;
    if (id.x >= cells || id.y >= cells) {
        return;
    }
    let s = level.step;
    let h = s / 2u;
    let x = id.x * s;
    let y = id.y * s;
    // Right of the corner: centres below and above, corners left and right.
    let across = (at(x + h, y + h) + at(x + h, y + level.size - h)) + (at(x, y) + at(x + s, y));
    textureStore(map, vec2<u32>(x + h, y), vec4<f32>(wibbled_mean(across, x + h, y), 0.0, 0.0, 0.0));
    // Below the corner: centres right and left, corners above and below.
    let down = (at(x + h, y + h) + at(x + level.size - h, y + h)) + (at(x, y) + at(x, y + s));
    textureStore(map, vec2<u32>(x, y + h), vec4<f32>(wibbled_mean(down, x, y + h), 0.0, 0.0, 0.0));
}
