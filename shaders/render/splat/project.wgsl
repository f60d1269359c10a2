// Projects each Gaussian (EWA splatting with the reference implementation's 0.3-pixel low-pass
// dilation), evaluates its colour from its spherical harmonics for the view direction, and
// writes its depth key (the float's bits, ordered like the depth) for the depth sort.
#include "common/linear_group.wgsl"
#include "render/splat/types.wgsl"

// A Gaussian as uploaded: mean, opacity (activated), 3D covariance (xx xy xz, yy yz zz).
struct Gaussian {
    mean: vec3<f32>,
    opacity: f32,
    cov_a: vec3<f32>,
    pad0: f32,
    cov_b: vec3<f32>,
    pad1: f32,
}

@group(0) @binding(0) var<uniform> camera: SplatCamera;
@group(0) @binding(1) var<storage, read> gaussians: array<Gaussian>;
@group(0) @binding(2) var<storage, read> sh: array<f32>;
@group(0) @binding(3) var<storage, read_write> splats: array<Splat>;
@group(0) @binding(4) var<storage, read_write> depth_keys: array<u32>;
@group(0) @binding(5) var<storage, read_write> order: array<u32>;

// Gaussians nearer than this to the camera plane are culled (the reference implementation's).
const NEAR_CULL: f32 = 0.2;

fn coefficient(gaussian: u32, k: u32) -> vec3<f32> {
    let count = (camera.sh_degree + 1u) * (camera.sh_degree + 1u);
    let at = (gaussian * count + k) * 3u;
    return vec3<f32>(sh[at], sh[at + 1u], sh[at + 2u]);
}

// Real spherical harmonics to degree 3 in the reference implementation's sign convention.
fn sh_color(gaussian: u32, dir: vec3<f32>) -> vec3<f32> {
    var c = 0.28209479177387814 * coefficient(gaussian, 0u);
    let x = dir.x;
    let y = dir.y;
    let z = dir.z;
    if camera.sh_degree > 0u {
        c += 0.4886025119029199 * (-y * coefficient(gaussian, 1u) + z * coefficient(gaussian, 2u)
            - x * coefficient(gaussian, 3u));
    }
    if camera.sh_degree > 1u {
        let xx = x * x;
        let yy = y * y;
        let zz = z * z;
        c += 1.0925484305920792 * x * y * coefficient(gaussian, 4u)
            - 1.0925484305920792 * y * z * coefficient(gaussian, 5u)
            + 0.31539156525252005 * (2.0 * zz - xx - yy) * coefficient(gaussian, 6u)
            - 1.0925484305920792 * x * z * coefficient(gaussian, 7u)
            + 0.5462742152960396 * (xx - yy) * coefficient(gaussian, 8u);
        if camera.sh_degree > 2u {
            c += -0.5900435899266435 * y * (3.0 * xx - yy) * coefficient(gaussian, 9u)
                + 2.890611442640554 * x * y * z * coefficient(gaussian, 10u)
                - 0.4570457994644658 * y * (4.0 * zz - xx - yy) * coefficient(gaussian, 11u)
                + 0.3731763325901154 * z * (2.0 * zz - 3.0 * xx - 3.0 * yy) * coefficient(gaussian, 12u)
                - 0.4570457994644658 * x * (4.0 * zz - xx - yy) * coefficient(gaussian, 13u)
                + 1.445305721320277 * z * (xx - yy) * coefficient(gaussian, 14u)
                - 0.5900435899266435 * x * (xx - 3.0 * yy) * coefficient(gaussian, 15u);
        }
    }
    return max(c + 0.5, vec3<f32>(0.0));
}

fn culled(i: u32) {
    splats[i].tile_min = vec2<u32>(0u);
    splats[i].tile_max = vec2<u32>(0u);
    depth_keys[i] = 0xffffffffu;
}

@compute @workgroup_size(256)
fn main(
    @builtin(local_invocation_index) t: u32,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let i = linear_group(group, groups) * 256u + t;
    if i >= camera.count {
        return;
    }
    order[i] = i;
    let g = gaussians[i];
    let p = (camera.camera_from_world * vec4<f32>(g.mean, 1.0)).xyz;
    if p.z <= NEAR_CULL {
        culled(i);
        return;
    }
    let slope = clamp(p.xy / p.z, camera.slope_min, camera.slope_max);
    let tx = slope.x * p.z;
    let ty = slope.y * p.z;
    let f = camera.focal;
    // Rows of the projection's Jacobian at the (clamped) mean.
    let j0 = vec3<f32>(f.x / p.z, 0.0, -f.x * tx / (p.z * p.z));
    let j1 = vec3<f32>(0.0, f.y / p.z, -f.y * ty / (p.z * p.z));
    let rotation = mat3x3<f32>(
        camera.camera_from_world[0].xyz,
        camera.camera_from_world[1].xyz,
        camera.camera_from_world[2].xyz,
    );
    let cov = mat3x3<f32>(
        vec3<f32>(g.cov_a.x, g.cov_a.y, g.cov_a.z),
        vec3<f32>(g.cov_a.y, g.cov_b.x, g.cov_b.y),
        vec3<f32>(g.cov_a.z, g.cov_b.y, g.cov_b.z),
    );
    let view_cov = rotation * cov * transpose(rotation);
    let a = dot(j0, view_cov * j0) + 0.3;
    let b = dot(j0, view_cov * j1);
    let c = dot(j1, view_cov * j1) + 0.3;
    let det = a * c - b * b;
    if det <= 0.0 {
        culled(i);
        return;
    }
    let mid = 0.5 * (a + c);
    let largest = mid + sqrt(max(0.1, mid * mid - det));
    let radius = ceil(3.0 * sqrt(largest));
    let pixel = f * p.xy / p.z + camera.principal;
    let tiles = vec2<f32>(camera.tiles);
    let tile_min = vec2<u32>(clamp(floor((pixel - radius) / f32(TILE)), vec2<f32>(0.0), tiles));
    let tile_max = vec2<u32>(clamp(floor((pixel + radius + f32(TILE) - 1.0) / f32(TILE)), vec2<f32>(0.0), tiles));
    if any(tile_max <= tile_min) {
        culled(i);
        return;
    }
    let dir = normalize(g.mean - camera.position);
    splats[i] = Splat(
        pixel,
        p.z,
        g.opacity,
        vec3<f32>(c, -b, a) / det,
        0.0,
        sh_color(i, dir),
        0.0,
        tile_min,
        tile_max,
    );
    depth_keys[i] = bitcast<u32>(p.z);
}
