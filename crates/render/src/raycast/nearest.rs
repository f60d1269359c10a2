//! Nearest-surface query: branch-and-bound over the BVH2, children visited nearest box first.

use glam::{Vec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::triangle::Triangle;

/// The closest point of the mesh to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    pub distance: f32,
    pub point: Vec3,
    pub triangle: u32,
}

pub(super) fn nearest_surface(
    bvh: &Bvh2,
    triangles: &[Triangle],
    query: Vec3A,
) -> Option<SurfacePoint> {
    if triangles.is_empty() {
        return None;
    }
    let mut best: Option<SurfacePoint> = None;
    let mut best_sq = f32::INFINITY;
    let mut stack = vec![(0u32, box_distance_sq(bvh.nodes[0].aabb(), query))];
    while let Some((index, dist_sq)) = stack.pop() {
        if dist_sq >= best_sq {
            continue;
        }
        let node = &bvh.nodes[index as usize];
        if node.is_leaf() {
            for slot in node.first_index..node.first_index + node.prim_count {
                let triangle = bvh.primitive_indices[slot as usize];
                let point = closest_point_on_triangle(&triangles[triangle as usize], query);
                let d_sq = point.distance_squared(query);
                if d_sq < best_sq {
                    best_sq = d_sq;
                    best = Some(SurfacePoint {
                        distance: d_sq.sqrt(),
                        point: point.into(),
                        triangle,
                    });
                }
            }
            continue;
        }
        let children = [node.first_index, node.first_index + 1]
            .map(|c| (c, box_distance_sq(bvh.nodes[c as usize].aabb(), query)));
        // Push the farther child first so the nearer one is searched first.
        let (near, far) = if children[0].1 <= children[1].1 {
            (children[0], children[1])
        } else {
            (children[1], children[0])
        };
        stack.push(far);
        stack.push(near);
    }
    best
}

fn box_distance_sq(aabb: &Aabb, p: Vec3A) -> f32 {
    let d = (aabb.min - p).max(p - aabb.max).max(Vec3A::ZERO);
    d.length_squared()
}

/// Ericson, Real-Time Collision Detection, §5.1.5.
fn closest_point_on_triangle(t: &Triangle, p: Vec3A) -> Vec3A {
    let (a, b, c) = (t.v0, t.v1, t.v2);
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}
