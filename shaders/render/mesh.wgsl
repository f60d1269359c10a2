// Rasterizes the scene mesh: sRGB colour (through an sRGB render view, so shading is linear) and
// metric z-depth along the optical axis into an R32Float target; with actors (`fs_mask`), also
// each pixel's object id into an R32Uint target (0 the static scene, k walker k).
#include "common/color.wgsl"

struct Camera {
    // world → camera (OpenCV axes: x right, y down, z forward)
    camera_from_world: mat4x4<f32>,
    // camera → clip, built from pinhole intrinsics with the +0.5 px principal-point shift
    clip_from_camera: mat4x4<f32>,
}

@group(0) @binding(0) var<uniform> camera: Camera;
@group(0) @binding(1) var textures: texture_2d_array<f32>;
@group(0) @binding(2) var texture_sampler: sampler;

// The light mix (crates/render/src/raster/light_mix.rs): with count 0 the baked vertex colours,
// else the sum of the scene's light layers, each times its weight, clamped as the baked 8-bit
// colours are.
const MAX_LIGHT_LAYERS: u32 = 8u;
struct LightMix {
    count: u32,
    weights: array<vec4<f32>, MAX_LIGHT_LAYERS>,
}
@group(0) @binding(3) var<uniform> light_mix: LightMix;
// Linear colour per vertex and layer, vertex-major.
@group(0) @binding(4) var<storage, read> light_layers: array<vec4<f32>>;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) uv: vec2<f32>,
    @location(2) color: vec4<f32>,
    @location(3) layer: u32,
    @location(4) object: u32,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
    @location(1) linear_color: vec3<f32>,
    @location(2) camera_z: f32,
    @location(3) @interpolate(flat) layer: u32,
    @location(4) @interpolate(flat) object: u32,
}


@vertex
fn vs_main(v: VertexIn, @builtin(vertex_index) index: u32) -> VertexOut {
    let p_cam = camera.camera_from_world * vec4<f32>(v.position, 1.0);
    var out: VertexOut;
    out.clip = camera.clip_from_camera * p_cam;
    out.uv = v.uv;
    if light_mix.count == 0u {
        out.linear_color = srgb_to_linear(v.color.rgb);
    } else {
        var sum = vec3<f32>(0.0);
        for (var l = 0u; l < light_mix.count; l++) {
            sum += light_layers[index * light_mix.count + l].rgb * light_mix.weights[l].rgb;
        }
        out.linear_color = clamp(sum, vec3<f32>(0.0), vec3<f32>(1.0));
    }
    out.camera_z = p_cam.z;
    out.layer = v.layer;
    out.object = v.object;
    return out;
}

struct FragmentOut {
    @location(0) color: vec4<f32>,
    @location(1) depth: f32,
}

fn shade(in: VertexOut) -> FragmentOut {
    let texel = textureSample(textures, texture_sampler, in.uv, in.layer);
    var out: FragmentOut;
    out.color = vec4<f32>(in.linear_color * texel.rgb, 1.0);
    out.depth = in.camera_z;
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> FragmentOut {
    return shade(in);
}

struct FragmentWithMask {
    @location(0) color: vec4<f32>,
    @location(1) depth: f32,
    @location(2) object: u32,
}

@fragment
fn fs_mask(in: VertexOut) -> FragmentWithMask {
    let shaded = shade(in);
    return FragmentWithMask(shaded.color, shaded.depth, in.object);
}
