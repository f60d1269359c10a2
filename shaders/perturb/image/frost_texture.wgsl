// frost, texture pass (once per seed): a procedural frost texture, ice crystals on misted glass.
// Crystals grow from random nuclei on a jittered grid (three scales): six arms at 60 degrees (ice's
// hexagonal habit) with fern-like side branches at +-60 degrees that shorten toward the tip,
// over a low-frequency mist. Colours run from blue-grey mist to white-blue ice. Mirrored by
// `frost_texture` in crates/perturb/src/image/frost.rs.
#include "common/rng.wgsl"

struct Texture {
    key: vec4<u32>,
    // crystal cell size in pixels (large scale); the small scale is a third of it
    cell: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

@group(0) @binding(0) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(1) var<uniform> params: Texture;

const SIN60: f32 = 0.8660254;
const COT60: f32 = 0.57735026;

fn uniform4(cell: vec2<i32>, layer: u32, index: u32) -> vec4<f32> {
    let bits = rng_draw(params.key, vec4<u32>(bitcast<vec2<u32>>(cell), layer, index));
    return vec4<f32>(bits >> vec4<u32>(8u)) * (1.0 / 16777216.0);
}

// Brightness of one dendrite arm at local coordinates (t along the arm, n across it).
fn arm(t: f32, n: f32, length: f32, width: f32, spacing: f32) -> f32 {
    if (t < 0.0 || t > length) {
        return 0.0;
    }
    let fade = sqrt(1.0 - t / length);
    let stem = exp(-(n * n) / (width * width));
    // Side branches leave the stem at t0 = k * spacing at 60 degrees; the branch through this
    // point starts at t0 = t - |n| cot 60 and reaches |n| / sin 60 along itself.
    let start = t - abs(n) * COT60;
    let nearest = round(start / spacing) * spacing;
    let reach = abs(n) / SIN60;
    let branch_length = 0.45 * (length - nearest);
    var branch = 0.0;
    if (nearest > 0.0 && reach < branch_length) {
        let across = (start - nearest) * SIN60;
        let w = 0.7 * width;
        branch = exp(-(across * across) / (w * w)) * sqrt(1.0 - reach / branch_length);
    }
    return fade * max(stem, 0.8 * branch);
}

// The brightest crystal of one scale at pixel p.
fn crystals(p: vec2<f32>, cell: f32, layer: u32) -> f32 {
    let home = vec2<i32>(floor(p / cell));
    var best = 0.0;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let c = home + vec2<i32>(dx, dy);
            let r = uniform4(c, layer, 0u);
            let nucleus = (vec2<f32>(c) + 0.15 + 0.7 * r.xy) * cell;
            let d = p - nucleus;
            let length = cell * (0.55 + 0.6 * r.w);
            if (dot(d, d) > length * length) {
                continue;
            }
            let width = max(0.9, 0.018 * cell);
            let spacing = 0.12 * length;
            // Six arms, each with its own length and a few degrees of misalignment, so that
            // crystals grow ragged like frost rather than like snowflakes.
            for (var k = 0; k < 6; k++) {
                let a = uniform4(c, layer, u32(k) + 1u);
                let angle = 6.2831855 * r.z + f32(k) * 1.0471976 + 0.35 * (a.x - 0.5);
                let u = vec2<f32>(cos(angle), sin(angle));
                let t = dot(d, u);
                let n = u.x * d.y - u.y * d.x;
                best = max(best, arm(t, n, length * (0.25 + 0.75 * a.y), width, spacing));
            }
        }
    }
    return best;
}

// Smooth value noise, four octaves, in [0, 1].
fn mist(p: vec2<f32>, cell: f32) -> f32 {
    var sum = 0.0;
    var scale = 2.0 * cell;
    var weight = 0.5;
    for (var octave = 0u; octave < 4u; octave++) {
        let q = p / scale;
        let i = vec2<i32>(floor(q));
        let f = q - floor(q);
        let s = f * f * (3.0 - 2.0 * f);
        let a = uniform4(i, 10u + octave, 0u).x;
        let b = uniform4(i + vec2<i32>(1, 0), 10u + octave, 0u).x;
        let c = uniform4(i + vec2<i32>(0, 1), 10u + octave, 0u).x;
        let d = uniform4(i + vec2<i32>(1, 1), 10u + octave, 0u).x;
        sum += weight * mix(mix(a, b, s.x), mix(c, d, s.x), s.y);
        scale *= 0.5;
        weight *= 0.5;
    }
    return sum / 0.9375;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(output);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let p = vec2<f32>(id.xy) + 0.5;
    let large = crystals(p, params.cell, 0u);
    let small = crystals(p, params.cell / 3.0, 1u);
    let tiny = crystals(p, params.cell / 8.0, 2u);
    let haze = mist(p, params.cell);
    let ice = clamp(max(large, max(0.75 * small, 0.5 * tiny)) + 0.35 * haze - 0.1, 0.0, 1.0);
    let glass = vec3<f32>(0.42, 0.52, 0.60) * (0.75 + 0.5 * haze);
    let white = vec3<f32>(0.93, 0.96, 1.0);
    textureStore(output, id.xy, vec4<f32>(mix(glass, white, ice), 1.0));
}
