// Blends each 16×16 tile's Gaussians front to back, one workgroup a tile and one invocation a
// pixel, batches of 256 Gaussians loaded together: colour, and the expected (Σ wᵢ zᵢ / Σ wᵢ) or
// median depth (the Gaussian where transmittance falls below 0.5); pixels whose accumulated
// opacity stays under `min_opacity` get depth 0, no measurement.
#include "render/splat/types.wgsl"

@group(0) @binding(0) var<uniform> camera: SplatCamera;
@group(0) @binding(1) var<storage, read> splat_position: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> splat_conic: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> splat_color: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> instance_gaussians: array<u32>;
@group(0) @binding(5) var<storage, read> ranges: array<vec2<u32>>;
@group(0) @binding(6) var color_out: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(7) var depth_out: texture_storage_2d<r32float, write>;

// pixel.xy, depth, opacity
var<workgroup> batch_position: array<vec4<f32>, 256>;
// conic xx, xy, yy
var<workgroup> batch_conic: array<vec3<f32>, 256>;
var<workgroup> batch_color: array<vec3<f32>, 256>;

// The reference implementation's cut-offs: contributions under 1/255 are skipped, one alpha is
// at most 0.99, and a pixel stops once its transmittance would fall under 1e-4.
const MIN_ALPHA: f32 = 1.0 / 255.0;
const MAX_ALPHA: f32 = 0.99;
const MIN_TRANSMITTANCE: f32 = 0.0001;

@compute @workgroup_size(16, 16)
fn main(
    @builtin(workgroup_id) tile: vec3<u32>,
    @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(local_invocation_index) t: u32,
) {
    let pixel = tile.xy * TILE + local.xy;
    let inside = all(pixel < camera.size);
    let range = ranges[tile.y * camera.tiles.x + tile.x];
    let total = range.y - range.x;
    let rounds = (total + 255u) / 256u;
    let at = vec2<f32>(pixel);
    var transmittance = 1.0;
    var color = vec3<f32>(0.0);
    var depth_sum = 0.0;
    var median = 0.0;
    var done = !inside;
    for (var round = 0u; round < rounds; round++) {
        workgroupBarrier();
        let slot = range.x + round * 256u + t;
        if slot < range.y {
            let gaussian = instance_gaussians[slot];
            batch_position[t] = splat_position[gaussian];
            batch_conic[t] = splat_conic[gaussian].xyz;
            batch_color[t] = splat_color[gaussian].xyz;
        }
        workgroupBarrier();
        let batch = min(256u, total - round * 256u);
        for (var k = 0u; k < batch && !done; k++) {
            let position = batch_position[k];
            let conic = batch_conic[k];
            let d = position.xy - at;
            let power = -0.5 * (conic.x * d.x * d.x + conic.z * d.y * d.y) - conic.y * d.x * d.y;
            if power > 0.0 {
                continue;
            }
            let alpha = min(MAX_ALPHA, position.w * exp(power));
            if alpha < MIN_ALPHA {
                continue;
            }
            let next = transmittance * (1.0 - alpha);
            if next < MIN_TRANSMITTANCE {
                done = true;
                continue;
            }
            let weight = alpha * transmittance;
            color += batch_color[k] * weight;
            depth_sum += position.z * weight;
            if transmittance >= 0.5 && next < 0.5 {
                median = position.z;
            }
            transmittance = next;
        }
    }
    if !inside {
        return;
    }
    let opacity = 1.0 - transmittance;
    var depth = 0.0;
    if opacity >= camera.min_opacity && opacity > 0.0 {
        if camera.depth_mode == 0u {
            depth = depth_sum / opacity;
        } else {
            depth = median;
        }
    }
    textureStore(color_out, pixel, vec4<f32>(clamp(color, vec3<f32>(0.0), vec3<f32>(1.0)), 1.0));
    textureStore(depth_out, pixel, vec4<f32>(depth, 0.0, 0.0, 0.0));
}
