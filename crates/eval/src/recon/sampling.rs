//! Counter-based draws of points: draw i depends only on the key and i, so the points are the
//! same whatever the thread count.

use glam::{DVec3, Vec3};
use rayon::prelude::*;
use rslam_core::hash::splitmix64;
use rslam_core::mesh_io::MeshGeometry;

/// Uniform in [0, 1) for draw `counter` of the stream `key`.
fn uniform(key: u64, counter: u64) -> f64 {
    (splitmix64(key ^ splitmix64(counter)) >> 11) as f64 / (1u64 << 53) as f64
}

/// `n` points uniformly distributed by area over the mesh's triangles; `None` when their total
/// area is zero.
pub(super) fn sample_triangles(mesh: &MeshGeometry, n: usize, key: u64) -> Option<Vec<Vec3>> {
    let corner = |t: &[u32], k: usize| DVec3::from(mesh.positions[t[k] as usize].map(f64::from));
    let triangles: Vec<[DVec3; 3]> = mesh
        .indices
        .chunks_exact(3)
        .map(|t| [corner(t, 0), corner(t, 1), corner(t, 2)])
        .collect();
    let cumulative_area: Vec<f64> = triangles
        .iter()
        .scan(0.0, |sum, [a, b, c]| {
            *sum += (*b - *a).cross(*c - *a).length() / 2.0;
            Some(*sum)
        })
        .collect();
    let total = *cumulative_area.last()?;
    if total <= 0.0 {
        return None;
    }
    let points = (0..n as u64)
        .into_par_iter()
        .map(|i| {
            let pick = uniform(key, 3 * i) * total;
            // Zero-area triangles span no interval of the cumulative area and are never picked.
            let t = cumulative_area
                .partition_point(|&c| c <= pick)
                .min(triangles.len() - 1);
            let [a, b, c] = triangles[t];
            // Uniform on the triangle: Osada et al. 2002, "Shape distributions", eq. 1.
            let r1 = uniform(key, 3 * i + 1).sqrt();
            let r2 = uniform(key, 3 * i + 2);
            (a * (1.0 - r1) + b * (r1 * (1.0 - r2)) + c * (r1 * r2)).as_vec3()
        })
        .collect();
    Some(points)
}

/// All the points when there are at most `n`, else `n` of them drawn without replacement (the
/// `n` with the smallest hash of their index), in file order.
pub(super) fn sample_points(positions: &[[f32; 3]], n: usize, key: u64) -> Vec<Vec3> {
    let mut chosen: Vec<usize> = (0..positions.len()).collect();
    if positions.len() > n {
        chosen.select_nth_unstable_by_key(n, |&i| splitmix64(key ^ splitmix64(i as u64)));
        chosen.truncate(n);
        chosen.sort_unstable();
    }
    chosen.iter().map(|&i| Vec3::from(positions[i])).collect()
}
