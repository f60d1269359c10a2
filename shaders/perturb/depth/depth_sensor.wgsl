// depth_sensor: a structured-light / active-stereo depth sensor computed from the rendered depth
// and the camera. Entry points, in this order (the CPU twin is depth_sensor.rs with
// depth_sensor_geometry.rs):
//   geometry (per pixel, reads the rendered depth): θ between each pixel's surface normal and its
//     viewing ray, and the pixel whose measurement it shows once every depth edge moved along x
//     (else y) by its seeded shift (its own where no edge swept over it).
//   sense (one invocation per row, in place; the emitter is rectified with the camera, so
//     projector occlusion is a 1-D test along the row):
//   - projector shadow: scanning the row from the emitter's side, q(x) = side·x − f·|b|/z is the
//     pixel's projector column (mirrored so the emitter is at +x); a pixel is shadowed when q is
//     not below the running minimum of q over the pixels already scanned (nearer geometry on the
//     emitter's ray). Invalid pixels (0) are skipped.
//   - disparity d = F/z in the sensor's native pixels (F = native f·b), plus N(0, σ) with σ from
//     σ_d and the angle term (disparity_sigma), rounded to the disparity step
//     (floor(d/step + 0.5)), back to z' = F/d'.
//   - z' outside [z_min, z_max], or d' ≤ 0, becomes invalid (0).
//   (the sensed depth is copied to `sensed_in`)
//   lateral (per pixel): each pixel takes the measurement of its source.
#include "common/rng.wgsl"

struct Params {
    // noise draws
    key: vec4<u32>,
    // edge shift draws
    lateral_key: vec4<u32>,
    // x: f·|b| of the frame's camera (px·m), y: emitter side (+1: +x, −1: −x),
    // z: σ_d (native px), w: disparity step (native px)
    geometry: vec4<f32>,
    // x: F = native f·|b| (px·m), y: z_min, z: z_max (metres), w: angle term coefficient (m)
    sensor: vec4<f32>,
    // fx, fy, cx, cy of the frame's camera
    camera: vec4<f32>,
    // x, y: σ_L = x + y·θ/(π/2 − θ) (native px), z: reach (px), w: σ from which shifts are
    // rounded normals
    lateral: vec4<f32>,
    // x: largest θ (radians), y: tan of the edge angle, z: native f (px)
    limits: vec4<f32>,
}

@group(0) @binding(0) var depth: texture_storage_2d<r32float, read_write>;
@group(0) @binding(1) var<uniform> params: Params;
// per pixel, the index y·width + x of the pixel whose measurement it shows (exact below 2^24)
@group(0) @binding(2) var sources_out: texture_storage_2d<r32float, write>;
// θ of each pixel's surface
@group(0) @binding(3) var angle_out: texture_storage_2d<r32float, write>;
@group(0) @binding(4) var sources_in: texture_2d<f32>;
@group(0) @binding(5) var angle_in: texture_2d<f32>;
// the sensed depth, before the lateral moves
@group(0) @binding(6) var sensed_in: texture_2d<f32>;

// Above any projector column: the running minimum before the first valid pixel.
const NO_MINIMUM: f32 = 3.0e38;
const HALF_PI: f32 = 1.5707964;

fn inside(q: vec2<i32>) -> bool {
    let size = vec2<i32>(textureDimensions(depth));
    return q.x >= 0 && q.y >= 0 && q.x < size.x && q.y < size.y;
}

// The rendered depth at q, 0 outside the frame.
fn load(q: vec2<i32>) -> f32 {
    if (!inside(q)) {
        return 0.0;
    }
    return textureLoad(depth, vec2<u32>(q)).x;
}

// Whether neighbours of depths a and b along an axis of focal length f are on one surface.
fn continuous(a: f32, b: f32, f: f32) -> bool {
    return a > 0.0 && b > 0.0 && abs(a - b) <= params.limits.y / f * min(a, b);
}

// Whether an edge lies between neighbours: a jump, or a valid pixel beside an invalid one.
fn is_edge(a: f32, b: f32, f: f32) -> bool {
    return (a > 0.0 || b > 0.0) && !continuous(a, b, f);
}

// The difference of the back-projected points of pixels q1 and q0 at depths z1 and z0, written
// so nothing cancels: X1 − X0 = u1·(z1 − z0) + (x1 − x0)/fx·z0 with u = (x − cx)/fx.
fn difference(q1: vec2<i32>, z1: f32, q0: vec2<i32>, z0: f32) -> vec3<f32> {
    let c = params.camera;
    let dz = z1 - z0;
    return vec3<f32>(
        (f32(q1.x) - c.z) / c.x * dz + f32(q1.x - q0.x) / c.x * z0,
        (f32(q1.y) - c.w) / c.y * dz + f32(q1.y - q0.y) / c.y * z0,
        dz,
    );
}

// The surface's difference across q along `step`: central, one-sided where one neighbour is
// across an edge, zero where both are.
fn tangent(q: vec2<i32>, z: f32, step: vec2<i32>, f: f32) -> vec3<f32> {
    let before = q - step;
    let after = q + step;
    let a = load(before);
    let b = load(after);
    var q0 = q;
    var z0 = z;
    if (continuous(a, z, f)) {
        q0 = before;
        z0 = a;
    }
    var q1 = q;
    var z1 = z;
    if (continuous(b, z, f)) {
        q1 = after;
        z1 = b;
    }
    return difference(q1, z1, q0, z0);
}

// acos on [0, 1] to 2e-8 rad from +, ×, √ alone, as the twin computes it (a driver's acos may be
// off by far more): Abramowitz & Stegun 4.4.46.
fn acos_poly(x: f32) -> f32 {
    var p = -0.0012624911;
    p = p * x + 0.00667009;
    p = p * x - 0.017088126;
    p = p * x + 0.03089188;
    p = p * x - 0.050174305;
    p = p * x + 0.08897899;
    p = p * x - 0.2145988;
    p = p * x + 1.5707963;
    return sqrt(1.0 - x) * p;
}

// θ between the normal and the viewing ray at q, clamped; 0 where q is invalid or its normal is
// unknown.
fn angle(q: vec2<i32>) -> f32 {
    let z = load(q);
    if (z <= 0.0) {
        return 0.0;
    }
    let u = tangent(q, z, vec2<i32>(1, 0), params.camera.x);
    let v = tangent(q, z, vec2<i32>(0, 1), params.camera.y);
    let n = vec3<f32>(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
    let nn = n.x * n.x + n.y * n.y + n.z * n.z;
    if (nn == 0.0) {
        return 0.0;
    }
    let ray = vec3<f32>((f32(q.x) - params.camera.z) / params.camera.x, (f32(q.y) - params.camera.w) / params.camera.y, 1.0);
    let c = abs(n.x * ray.x + n.y * ray.y + n.z * ray.z)
        / sqrt(nn * (ray.x * ray.x + ray.y * ray.y + ray.z * ray.z));
    return min(acos_poly(min(c, 1.0)), params.limits.x);
}

// σ_L at the surface of `near`, in frame pixels along an axis of focal length f.
fn sigma_lateral(near: vec2<i32>, f: f32) -> f32 {
    let theta = angle(near);
    return (params.lateral.x + params.lateral.y * theta / (HALF_PI - theta)) * f / params.limits.z;
}

// The integer shift of the edge after `lo` along `axis`, of standard deviation σ px: a rounded
// normal of variance σ² − 1/12, or below lateral.w a step of ±1 with P(±1) = σ²/2.
fn shift(lo: vec2<i32>, axis: u32, sigma: f32) -> i32 {
    let u = rng_draw(params.lateral_key, vec4<u32>(u32(lo.x), u32(lo.y), axis, 0u));
    var s = 0.0;
    if (sigma >= params.lateral.w) {
        let n = rng_normal_pair(u.x, u.y).x;
        s = floor(sqrt(sigma * sigma - 1.0 / 12.0) * n + 0.5);
    } else {
        let v = rng_uniform(u.z);
        let p = sigma * sigma / 2.0;
        if (v < p) {
            s = -1.0;
        } else if (v >= 1.0 - p) {
            s = 1.0;
        }
    }
    return i32(clamp(s, -params.lateral.z, params.lateral.z));
}

// The pixel whose depth q takes after the nearest edge along `axis` (0: x, 1: y) within the reach
// moved: the growing side's pixel at the edge where the edge swept over q, else q.
fn source(q: vec2<i32>, axis: u32) -> vec2<i32> {
    let e = select(vec2<i32>(0, 1), vec2<i32>(1, 0), axis == 0u);
    let f = select(params.camera.y, params.camera.x, axis == 0u);
    let reach = i32(params.lateral.z);
    for (var d = 0; d < reach; d++) {
        for (var side = 0; side < 2; side++) {
            // The edge lies between lo and hi = lo + e, d + ½ pixels from q.
            let before = side == 0;
            let k = select(d, -(d + 1), before);
            let lo = q + k * e;
            let hi = lo + e;
            if (!inside(lo) || !inside(hi)) {
                continue;
            }
            let a = load(lo);
            let b = load(hi);
            if (!is_edge(a, b, f)) {
                continue;
            }
            let near = select(lo, hi, b > 0.0 && (a <= 0.0 || b < a));
            let s = shift(lo, axis, sigma_lateral(near, f));
            if (before && s > d) {
                return lo;
            }
            if (!before && -s > d) {
                return hi;
            }
            return q;
        }
    }
    return q;
}

@compute @workgroup_size(8, 8)
fn geometry(@builtin(global_invocation_id) id: vec3<u32>) {
    let q = vec2<i32>(id.xy);
    if (!inside(q)) {
        return;
    }
    var taken = source(q, 0u);
    if (all(taken == q)) {
        taken = source(q, 1u);
    }
    let width = i32(textureDimensions(depth).x);
    textureStore(sources_out, id.xy, vec4<f32>(f32(taken.y * width + taken.x)));
    textureStore(angle_out, id.xy, vec4<f32>(angle(q)));
}

// The disparity σ that gives σ_z(z) + σ_θ(z, θ): with a = σ_θ·F/z²,
// √(σ_d² + a² + 2a·√(σ_d² + step²/12)).
fn disparity_sigma(z: f32, theta: f32) -> f32 {
    let sigma = params.geometry.z;
    let step = params.geometry.w;
    let fb_native = params.sensor.x;
    let r = theta / (HALF_PI - theta);
    let a = params.sensor.w / sqrt(z) * (r * r) * fb_native / (z * z);
    let spread = sqrt(sigma * sigma + step * step / 12.0);
    return sqrt(sigma * sigma + a * a + 2.0 * a * spread);
}

@compute @workgroup_size(64)
fn sense(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(depth);
    let y = id.x;
    if (y >= size.y) {
        return;
    }
    let fb_frame = params.geometry.x;
    let side = params.geometry.y;
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
            let theta = textureLoad(angle_in, vec2<u32>(x, y), 0).x;
            let d = fb_native / z + disparity_sigma(z, theta) * n;
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

// Each pixel takes the measurement of its source (the sensed depth, copied to `sensed_in`).
@compute @workgroup_size(8, 8)
fn lateral(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(depth);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let src = u32(textureLoad(sources_in, id.xy, 0).x);
    let z = textureLoad(sensed_in, vec2<u32>(src % size.x, src / size.x), 0).x;
    textureStore(depth, id.xy, vec4<f32>(z));
}
