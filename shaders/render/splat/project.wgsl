// Projects each Gaussian (EWA splatting with the reference implementation's 0.3-pixel low-pass
// dilation) and evaluates its colour from its spherical harmonics for the view direction.
#include "common/linear_group.wgsl"
#include "render/splat/types.wgsl"

// The capture as uploaded, per Gaussian: mean and activated opacity, and the 3D covariance
// (xx xy xz, yy yz zz). The harmonics are bound a chunk of Gaussians at a time, from `chunk.first`.
struct Chunk {
    first: u32,
    count: u32,
}

@group(0) @binding(0) var<uniform> camera: SplatCamera;
@group(0) @binding(1) var<storage, read> mean_opacity: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> cov_a: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> cov_b: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> sh: array<f32>;
@group(0) @binding(5) var<storage, read_write> splat_position: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read_write> splat_conic: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> splat_color: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> splat_tiles: array<vec2<u32>>;
@group(0) @binding(9) var<uniform> chunk: Chunk;

// Gaussians nearer than this to the camera plane are culled (the reference implementation's).
const NEAR_CULL: f32 = 0.2;

// Coefficient k of the chunk's Gaussian `local`.
fn coefficient(local: u32, k: u32) -> vec3<f32> {
    let count = (camera.sh_degree + 1u) * (camera.sh_degree + 1u);
    let at = (local * count + k) * 3u;
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
    splat_tiles[i] = vec2<u32>(0u);
}

@compute @workgroup_size(256)
fn main(
    @builtin(local_invocation_index) t: u32,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let local = linear_group(group, groups) * 256u + t;
    if local >= chunk.count {
        return;
    }
    let i = chunk.first + local;
    let mean = mean_opacity[i].xyz;
    let a3 = cov_a[i].xyz;
    let b3 = cov_b[i].xyz;
    let p = (camera.camera_from_world * vec4<f32>(mean, 1.0)).xyz;
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
        vec3<f32>(a3.x, a3.y, a3.z),
        vec3<f32>(a3.y, b3.x, b3.y),
        vec3<f32>(a3.z, b3.y, b3.z),
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
    let dir = normalize(mean - camera.position);
    splat_position[i] = vec4<f32>(pixel, p.z, mean_opacity[i].w);
    splat_conic[i] = vec4<f32>(vec3<f32>(c, -b, a) / det, 0.0);
    splat_color[i] = vec4<f32>(sh_color(local, dir), 0.0);
    splat_tiles[i] = vec2<u32>(tile_pair(tile_min), tile_pair(tile_max));
}
