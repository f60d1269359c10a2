// depth_sensor: a structured-light / active-stereo depth sensor computed from the rendered depth
// and the camera, in place. One invocation per row (the emitter is rectified with the camera, so
// projector occlusion is a 1-D test along the row):
//   - projector shadow: scanning the row from the emitter's side, q(x) = side·x − f·|b|/z is the
//     pixel's projector column (mirrored so the emitter is at +x); a pixel is shadowed when q is
//     not below the running minimum of q over the pixels already scanned (nearer geometry on the
//     emitter's ray). Invalid pixels (0) are skipped.
//   - disparity d = F/z in the sensor's native pixels (F = native f·b), plus N(0, σ_d), rounded to
//     the disparity step (floor(d/step + 0.5)), back to z' = F/d'.
//   - z' outside [z_min, z_max], or d' ≤ 0, becomes invalid (0).
// The CPU twin is `depth_sensor.rs`.
#include "common/rng.wgsl"

struct Params {
    key: vec4<u32>,
    // x: f·|b| of the frame's camera (px·m), y: emitter side (+1: +x, −1: −x),
    // z: σ_d (native px), w: disparity step (native px)
    geometry: vec4<f32>,
    // x: F = native f·|b| (px·m), y: z_min, z: z_max (metres)
    sensor: vec4<f32>,
}

@group(0) @binding(0) var depth: texture_storage_2d<r32float, read_write>;
@group(0) @binding(1) var<uniform> params: Params;

// Above any projector column: the running minimum before the first valid pixel.
const NO_MINIMUM: f32 = 3.0e38;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(depth);
    let y = id.x;
    if (y >= size.y) {
        return;
    }
    let fb_frame = params.geometry.x;
    let side = params.geometry.y;
    let sigma = params.geometry.z;
    let step = params.geometry.w;
    let fb_native = params.sensor.x;
    var running = NO_MINIMUM;
    for (var i = 0u; i < size.x; i++) {
        // Start at the emitter's side of the row.
        let x = select(i, size.x - 1u - i, side > 0.0);
        let z = textureLoad(depth, vec2<u32>(x, y)).x;
        if (z <= 0.0) {
            continue;
        }
        let q = side * f32(x) - fb_frame / z;
        let shadowed = q >= running;
        running = min(running, q);
        var out = 0.0;
        if (!shadowed) {
            let u = rng_draw(params.key, vec4<u32>(x, y, 0u, 0u));
            let n = rng_normal_pair(u.x, u.y).x;
            let d = fb_native / z + sigma * n;
            let dq = floor(d / step + 0.5) * step;
            if (dq > 0.0) {
                let zq = fb_native / dq;
                if (zq >= params.sensor.y && zq <= params.sensor.z) {
                    out = zq;
                }
            }
        }
        textureStore(depth, vec2<u32>(x, y), vec4<f32>(out));
    }
}
