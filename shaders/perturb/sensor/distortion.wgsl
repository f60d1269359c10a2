// distortion: the frame seen through a lens. Each output (lens) pixel looks up where its ray
// lands in the wider pinhole render (`lookup`, made on the CPU by inverting the lens model) and
// samples there: colour bilinearly in linear light; depth bilinearly only where the four texels
// agree (one surface), else from the nearest texel, so that no depth mixes two surfaces.
#include "common/color.wgsl"

// Four depths agree when they span at most this fraction of the nearest: a plane 80° off the
// view direction changes z by about 1 % per pixel at f = 600; object edges indoors jump more.
const DEPTH_AGREE: f32 = 0.02;

@group(0) @binding(0) var wide_color: texture_2d<f32>;
@group(0) @binding(1) var wide_depth: texture_2d<f32>;
@group(0) @binding(2) var<storage, read> lookup: array<vec2<f32>>;
@group(0) @binding(3) var color_out: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(4) var depth_out: texture_storage_2d<r32float, write>;

fn light(p: vec2<i32>) -> vec3<f32> {
    return srgb_to_linear(textureLoad(wide_color, p, 0).rgb);
}

fn z(p: vec2<i32>) -> f32 {
    return textureLoad(wide_depth, p, 0).r;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(color_out);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let at = lookup[id.y * size.x + id.x];
    let last = vec2<i32>(textureDimensions(wide_color)) - vec2<i32>(1);
    let base = floor(at);
    let t = at - base;
    let p00 = clamp(vec2<i32>(base), vec2<i32>(0), last);
    let p11 = clamp(vec2<i32>(base) + vec2<i32>(1), vec2<i32>(0), last);
    let p10 = vec2<i32>(p11.x, p00.y);
    let p01 = vec2<i32>(p00.x, p11.y);
    let c = mix(mix(light(p00), light(p10), t.x), mix(light(p01), light(p11), t.x), t.y);
    textureStore(color_out, id.xy, vec4<f32>(linear_to_srgb(c), 1.0));

    let d = vec4<f32>(z(p00), z(p10), z(p01), z(p11));
    let low = min(min(d.x, d.y), min(d.z, d.w));
    let high = max(max(d.x, d.y), max(d.z, d.w));
    var depth: f32;
    if (low > 0.0 && high - low <= DEPTH_AGREE * low) {
        depth = mix(mix(d.x, d.y, t.x), mix(d.z, d.w, t.x), t.y);
    } else {
        let nearest_top = select(d.x, d.y, t.x >= 0.5);
        let nearest_bottom = select(d.z, d.w, t.x >= 0.5);
        depth = select(nearest_top, nearest_bottom, t.y >= 0.5);
    }
    textureStore(depth_out, id.xy, vec4<f32>(depth, 0.0, 0.0, 0.0));
}

// Instance masks: the id of the nearest texel, the one depth takes where surfaces do not agree.
@group(0) @binding(5) var wide_mask: texture_2d<u32>;
@group(0) @binding(6) var mask_out: texture_storage_2d<r32uint, write>;

@compute @workgroup_size(8, 8)
fn mask_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(mask_out);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let at = lookup[id.y * size.x + id.x];
    let last = vec2<i32>(textureDimensions(wide_mask)) - vec2<i32>(1);
    let base = floor(at);
    let nearest = vec2<i32>(base) + vec2<i32>(at - base >= vec2<f32>(0.5));
    textureStore(mask_out, id.xy, vec4<u32>(textureLoad(wide_mask, clamp(nearest, vec2<i32>(0), last), 0).r));
}
