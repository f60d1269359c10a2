//! The scene's exposure, metered like a camera's auto-exposure on the room: the median radiance
//! of the surfaces, weighted by their area, is put at a mid tone, so walls, floor and furniture
//! sit inside the sensor's range and only the spots next to lamps and windows saturate.
//!
//! Weighting by area, not by vertex, matters: furniture has many small faces hidden in shadow
//! (under seats, inside shelves), and a per-vertex median over them exposes the open surfaces so
//! brightly that most of the picture clips.

use glam::Vec3;

use crate::Mesh;

/// Linear luminance of the area-weighted median surface (sRGB 0.30). The open walls and floor,
/// lit more than the average surface, land at sRGB 0.36–0.59, and a frame's mean near the
/// mid-grey (18 % linear, sRGB 0.46) that a camera's auto-exposure aims for: along the default
/// paths the median frame mean is 0.46 in room0 and 0.50 in office0. Twice this value (0.60 and
/// 0.62) exposed a stop brighter than a camera would.
const MEDIAN_RADIANCE: f32 = 0.075;

const LUMA: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);

/// The factor that exposes `radiance` (linear, per vertex, before exposure); glowing vertices are
/// not metered.
pub fn exposure(mesh: &Mesh, radiance: &[Vec3], emissive: &[bool]) -> f32 {
    let mut area = vec![0.0f32; mesh.vertices.len()];
    for t in mesh.indices.chunks_exact(3) {
        let p = |i: usize| Vec3::from(mesh.vertices[t[i] as usize].position);
        let third = (p(1) - p(0)).cross(p(2) - p(0)).length() / 6.0;
        for &i in t {
            area[i as usize] += third;
        }
    }
    let mut metered: Vec<(f32, f32)> = radiance
        .iter()
        .zip(&area)
        .zip(emissive)
        .filter(|&((_, &a), &glows)| !glows && a > 0.0)
        .map(|((r, &a), _)| (r.dot(LUMA), a))
        .collect();
    metered.sort_by(|a, b| a.0.total_cmp(&b.0));
    let half = metered.iter().map(|m| m.1).sum::<f32>() / 2.0;
    let mut below = 0.0;
    let median = metered
        .iter()
        .find(|m| {
            below += m.1;
            below >= half
        })
        .map_or(0.0, |m| m.0);
    if median > 0.0 {
        MEDIAN_RADIANCE / median
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Vertex;

    fn quad(mesh: &mut Mesh, x: f32, size: f32, cells: u32) {
        let step = size / cells as f32;
        for i in 0..cells {
            for j in 0..cells {
                let base = mesh.vertices.len() as u32;
                for (di, dj) in [(0, 0), (1, 0), (1, 1), (0, 1)] {
                    mesh.vertices.push(Vertex {
                        position: [x + (i + di) as f32 * step, (j + dj) as f32 * step, 0.0],
                        uv: [0.0; 2],
                        color: [255; 4],
                        layer: 0,
                    });
                }
                mesh.indices
                    .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
            }
        }
    }

    #[test]
    fn the_larger_surface_sets_the_exposure_however_many_vertices_the_smaller_has() {
        let mut mesh = Mesh::default();
        quad(&mut mesh, 0.0, 4.0, 1); // a wall: 4 vertices, 16 m²
        let wall = mesh.vertices.len();
        quad(&mut mesh, 10.0, 1.0, 20); // a shelf in shadow: 1600 vertices, 1 m²
        let mut radiance = vec![Vec3::splat(0.5); wall];
        radiance.resize(mesh.vertices.len(), Vec3::splat(0.01));
        let emissive = vec![false; mesh.vertices.len()];
        let e = exposure(&mesh, &radiance, &emissive);
        assert!((0.5 * e - MEDIAN_RADIANCE).abs() < 1e-6, "exposure {e}");
    }

    #[test]
    fn glowing_vertices_are_not_metered() {
        let mut mesh = Mesh::default();
        quad(&mut mesh, 0.0, 1.0, 1);
        quad(&mut mesh, 10.0, 3.0, 1);
        let radiance = [vec![Vec3::splat(0.2); 4], vec![Vec3::splat(5.0); 4]].concat();
        let emissive = [vec![false; 4], vec![true; 4]].concat();
        let e = exposure(&mesh, &radiance, &emissive);
        assert!((0.2 * e - MEDIAN_RADIANCE).abs() < 1e-6, "exposure {e}");
    }
}
