// depth_colormap: metric z-depth → Turbo colours (sRGB-encoded) for display; no depth (0) → black.
// Turbo as the polynomial fit of Ruofei Du (Google, 2019, "Turbo colormap, polynomial
// approximation"); the CPU twin is `rslam_pipeline::depth_colormap::turbo`.

struct Params {
    // x: near metres (first colour), y: far metres (last colour)
    range: vec4<f32>,
}

@group(0) @binding(0) var depth: texture_storage_2d<r32float, read_write>;
@group(0) @binding(1) var colors: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Params;

fn turbo(x: f32) -> vec3<f32> {
    let red4 = vec4<f32>(0.13572138, 4.61539260, -42.66032258, 132.13108234);
    let green4 = vec4<f32>(0.09140261, 2.19418839, 4.84296658, -14.18503333);
    let blue4 = vec4<f32>(0.10667330, 12.64194608, -60.58204836, 110.36276771);
    let red2 = vec2<f32>(-152.94239396, 59.28637943);
    let green2 = vec2<f32>(4.27729857, 2.82956604);
    let blue2 = vec2<f32>(-89.90310912, 27.34824973);
    let t = clamp(x, 0.0, 1.0);
    let v4 = vec4<f32>(1.0, t, t * t, t * t * t);
    let v2 = v4.zw * v4.z;
    let rgb = vec3<f32>(
        dot(v4, red4) + dot(v2, red2),
        dot(v4, green4) + dot(v2, green2),
        dot(v4, blue4) + dot(v2, blue2),
    );
    return clamp(rgb, vec3<f32>(0.0), vec3<f32>(1.0));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(depth);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let z = textureLoad(depth, id.xy).x;
    var rgb = vec3<f32>(0.0);
    if (z > 0.0) {
        let span = max(params.range.y - params.range.x, 1e-6);
        rgb = turbo((z - params.range.x) / span);
    }
    textureStore(colors, id.xy, vec4<f32>(rgb, 1.0));
}
