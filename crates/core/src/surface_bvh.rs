//! Triangles in a BVH (obvhs BVH2) and the two queries over it: the nearest surface point
//! (branch-and-bound, children visited nearest box first) and the first hit along a ray
//! (Möller–Trumbore, its barycentric bounds widened by [`EDGE_EPS`] so that a ray through an edge
//! two triangles share never slips between them). The renderer's ray-cast oracle and the mapping
//! metrics' visibility test both cast through it.

use std::time::Duration;

use glam::{Vec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::bvh2::builder::build_bvh2_from_tris;
use obvhs::bvh2::Bvh2;
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;

use crate::mesh_io::MeshGeometry;

/// Barycentric slack so rays through shared edges hit one of the two triangles.
const EDGE_EPS: f32 = 1e-6;

/// The first triangle a ray meets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RaySurfaceHit {
    /// Along the ray, in units of its direction vector.
    pub t: f32,
    pub triangle: u32,
}

/// The closest point of the surface to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    pub distance: f32,
    pub point: Vec3,
    pub triangle: u32,
}

pub struct SurfaceBvh {
    bvh: Bvh2,
    triangles: Vec<Triangle>,
}

impl SurfaceBvh {
    /// Builds the BVH over `triangles`. A triangle with three equal corners is a point, so a
    /// point cloud is a surface too (its nearest point is its nearest surface point).
    pub fn new(triangles: Vec<Triangle>) -> Self {
        let bvh = if triangles.is_empty() {
            Bvh2::default()
        } else {
            build_bvh2_from_tris(
                &triangles,
                BvhBuildParams::fast_build(),
                &mut Duration::default(),
            )
        };
        Self { bvh, triangles }
    }

    /// The triangles of a mesh file, or its vertices where it is a point cloud.
    pub fn of_geometry(geometry: &MeshGeometry) -> Self {
        let p = |i: u32| Vec3A::from(geometry.positions[i as usize]);
        let triangle = |[a, b, c]: [u32; 3]| Triangle {
            v0: p(a),
            v1: p(b),
            v2: p(c),
        };
        let triangles = if geometry.is_point_cloud() {
            (0..geometry.positions.len() as u32)
                .map(|i| triangle([i; 3]))
                .collect()
        } else {
            geometry
                .indices
                .chunks_exact(3)
                .map(|t| triangle([t[0], t[1], t[2]]))
                .collect()
        };
        Self::new(triangles)
    }

    pub fn bvh(&self) -> &Bvh2 {
        &self.bvh
    }

    /// In the order given to [`SurfaceBvh::new`]; the BVH's primitive indices point here.
    pub fn triangles(&self) -> &[Triangle] {
        &self.triangles
    }

    /// The first hit of the ray `origin + t·dir` with `0 < t ≤ max_t` (`dir` need not be unit
    /// length); triangles are hit from either side.
    pub fn first_hit(&self, origin: Vec3, dir: Vec3, max_t: f32) -> Option<RaySurfaceHit> {
        if self.triangles.is_empty() || dir == Vec3::ZERO {
            return None;
        }
        let bvh = &self.bvh;
        let ray = Ray::new(origin.into(), dir.into(), 0.0, max_t);
        let mut hit = RayHit::none();
        let found = bvh.ray_traverse(ray, &mut hit, |ray, id| {
            intersect(&self.triangles[bvh.primitive_indices[id] as usize], ray)
        });
        found.then(|| RaySurfaceHit {
            t: hit.t,
            triangle: bvh.primitive_indices[hit.primitive_id as usize],
        })
    }

    /// Whether the ray `origin + t·dir` meets the surface anywhere with `min_t < t < max_t`: an
    /// occlusion test, which stops at the first triangle found instead of looking for the
    /// nearest (so it is fastest when the ray starts where occluders are likely).
    pub fn is_blocked(&self, origin: Vec3, dir: Vec3, min_t: f32, max_t: f32) -> bool {
        if self.triangles.is_empty() || dir == Vec3::ZERO {
            return false;
        }
        let bvh = &self.bvh;
        let ray = Ray::new(origin.into(), dir.into(), min_t, max_t);
        !bvh.ray_traverse_miss(ray, |ray, id| {
            intersect(&self.triangles[bvh.primitive_indices[id] as usize], ray)
        })
    }

    /// The surface point nearest to `query` (`None` for an empty surface).
    pub fn nearest(&self, query: Vec3) -> Option<SurfacePoint> {
        if self.triangles.is_empty() {
            return None;
        }
        let (bvh, query) = (&self.bvh, Vec3A::from(query));
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
                    let point =
                        closest_point_on_triangle(&self.triangles[triangle as usize], query);
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
}

/// The ray's parameter where it meets the triangle, or infinity where it does not.
fn intersect(tri: &Triangle, ray: &Ray) -> f32 {
    let e1 = tri.v1 - tri.v0;
    let e2 = tri.v2 - tri.v0;
    let p = ray.direction.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return f32::INFINITY;
    }
    let inv = 1.0 / det;
    let s = ray.origin - tri.v0;
    let u = s.dot(p) * inv;
    let q = s.cross(e1);
    let v = ray.direction.dot(q) * inv;
    if u < -EDGE_EPS || v < -EDGE_EPS || u + v > 1.0 + EDGE_EPS {
        return f32::INFINITY;
    }
    let t = e2.dot(q) * inv;
    if t > ray.tmin && t <= ray.tmax {
        t
    } else {
        f32::INFINITY
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_on_a_point_cloud_is_the_nearest_point() {
        let points: Vec<Vec3> = (0..500)
            .map(|i| {
                let h = crate::hash::splitmix64(i);
                let coordinate = |shift: u32| ((h >> shift) & 0xffff) as f32 / 65535.0 * 4.0 - 2.0;
                Vec3::new(coordinate(0), coordinate(16), coordinate(32))
            })
            .collect();
        let cloud = SurfaceBvh::of_geometry(&MeshGeometry {
            positions: points.iter().map(|p| p.to_array()).collect(),
            ..Default::default()
        });
        for q in [
            Vec3::ZERO,
            Vec3::new(3.0, -1.0, 0.5),
            Vec3::new(0.1, 0.2, -1.9),
        ] {
            let brute = points
                .iter()
                .map(|p| p.distance(q))
                .fold(f32::INFINITY, f32::min);
            let got = cloud.nearest(q).unwrap();
            assert_eq!(got.distance, brute, "{q}");
            assert_eq!(got.point, points[got.triangle as usize]);
        }
        let single = SurfaceBvh::of_geometry(&MeshGeometry {
            positions: vec![[1.0, 2.0, 3.0]],
            ..Default::default()
        });
        assert_eq!(
            single.nearest(Vec3::new(1.0, 2.0, 5.0)).unwrap().distance,
            2.0
        );
    }

    #[test]
    fn first_hit_is_the_nearer_of_two_planes_from_either_side_within_max_t() {
        let square = |z: f32| {
            let corner = |x: f32, y: f32| Vec3A::new(x, y, z);
            [
                Triangle {
                    v0: corner(-1.0, -1.0),
                    v1: corner(1.0, -1.0),
                    v2: corner(1.0, 1.0),
                },
                Triangle {
                    v0: corner(-1.0, -1.0),
                    v1: corner(1.0, 1.0),
                    v2: corner(-1.0, 1.0),
                },
            ]
        };
        let surface = SurfaceBvh::new([square(2.0), square(4.0)].concat());
        let dir = Vec3::new(0.1, 0.1, 2.0);
        let hit = surface.first_hit(Vec3::ZERO, dir, f32::INFINITY).unwrap();
        assert!((hit.t - 1.0).abs() < 1e-6 && hit.triangle < 2, "{hit:?}");
        // Through the diagonal the two triangles share.
        let diagonal = surface.first_hit(Vec3::ZERO, Vec3::new(0.5, 0.5, 2.0), 10.0);
        assert!(diagonal.is_some_and(|h| h.triangle < 2));
        assert!(surface.first_hit(Vec3::ZERO, dir, 0.99).is_none());
        let back = surface.first_hit(Vec3::new(0.0, 0.0, 6.0), -dir, f32::INFINITY);
        assert!(back.is_some_and(|h| (h.t - 1.0).abs() < 1e-6 && h.triangle >= 2));
        assert!(surface.first_hit(Vec3::ZERO, -dir, f32::INFINITY).is_none());
        assert!(surface.first_hit(Vec3::ZERO, Vec3::ZERO, 1.0).is_none());
        // The occlusion test agrees with the first hit on either side of max_t, and min_t
        // leaves out what lies before it.
        for (origin, dir, max_t) in [
            (Vec3::ZERO, dir, 1.01),
            (Vec3::ZERO, dir, 0.99),
            (Vec3::new(0.0, 0.0, 3.0), dir, 0.6),
            (Vec3::new(0.0, 0.0, 3.0), -dir, 0.4),
            (Vec3::ZERO, -dir, 100.0),
        ] {
            let first = surface.first_hit(origin, dir, max_t).is_some();
            let blocked = surface.is_blocked(origin, dir, 0.0, max_t);
            assert_eq!(blocked, first, "{origin} {dir} {max_t}");
        }
        assert!(
            surface.is_blocked(Vec3::ZERO, dir, 1.5, 2.5),
            "the far plane"
        );
        assert!(
            !surface.is_blocked(Vec3::ZERO, dir, 1.01, 1.99),
            "between the planes"
        );
    }

    #[test]
    fn nearest_on_a_triangle_is_inside_or_on_its_edge() {
        let triangle = Triangle {
            v0: Vec3A::ZERO,
            v1: Vec3A::X,
            v2: Vec3A::Y,
        };
        let surface = SurfaceBvh::new(vec![triangle]);
        let above = surface.nearest(Vec3::new(0.25, 0.25, 0.3)).unwrap();
        assert_eq!(above.point, Vec3::new(0.25, 0.25, 0.0));
        assert!((above.distance - 0.3).abs() < 1e-6);
        let beyond_the_edge = surface.nearest(Vec3::new(1.0, 1.0, 0.0)).unwrap();
        assert!((beyond_the_edge.point - Vec3::new(0.5, 0.5, 0.0)).length() < 1e-6);
        assert!(SurfaceBvh::new(Vec::new()).nearest(Vec3::ZERO).is_none());
    }
}
