//! CPU ray-cast oracle: the reference the rasterizer's depth (and colour) is tested against, and
//! the tool the built-in scenes' checks use to look through their default trajectories.
//!
//! Rays are traced through the scene's [`SurfaceBvh`] (its first-hit query).

mod shading;

use glam::{DVec3, Vec3, Vec3A};
use obvhs::triangle::Triangle;
use rayon::prelude::*;
pub use rslam_core::SurfacePoint;
use rslam_core::{DepthImage, Intrinsics, Pose, RgbImage, SurfaceBvh};

use crate::{Mesh, Scene, Texture};
use shading::Shading;
pub use shading::UvDerivatives;

/// Two triangles lie in one plane when their unit normals' dot product is at least this
/// (about 0.8°) ...
const SAME_PLANE_COS: f32 = 1.0 - 1e-4;
/// ... and each one's first corner is within this many metres of the other's plane (decals and
/// rugs sit a few millimetres above what they cover).
const SAME_PLANE_OFFSET: f32 = 5e-4;

/// The closest intersection along a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Along the ray, in units of the direction vector given to [`RayCaster::cast`] (metres for a
    /// unit direction; z-depth for a camera ray with unit z component).
    pub distance: f32,
    /// Index of the triangle (indices `3·triangle .. 3·triangle + 3` of the mesh).
    pub triangle: u32,
    /// Weights of the triangle's three vertices at the hit point (they sum to 1).
    pub barycentrics: [f32; 3],
}

/// Colour and depth of one view, both ray-cast, and the triangle each pixel sees.
pub struct RayCastFrame {
    pub rgb: RgbImage,
    pub depth: DepthImage,
    /// Row-major, one per pixel; `None` where the ray misses.
    pub triangles: Vec<Option<u32>>,
}

pub struct RayCaster {
    surface: SurfaceBvh,
    shading: Shading,
}

impl RayCaster {
    /// Builds the BVH over the scene's triangles and the mip chains of its textures.
    pub fn new(scene: &Scene) -> Self {
        Self::build(&scene.mesh, &scene.textures)
    }

    /// Geometry only: colours are the vertex colours (every layer samples white).
    pub fn from_mesh(mesh: &Mesh) -> Self {
        Self::build(mesh, &[Texture::white()])
    }

    fn build(mesh: &Mesh, textures: &[Texture]) -> Self {
        let p = |i: u32| Vec3A::from(mesh.vertices[i as usize].position);
        let triangles: Vec<Triangle> = mesh
            .indices
            .chunks_exact(3)
            .map(|t| Triangle {
                v0: p(t[0]),
                v1: p(t[1]),
                v2: p(t[2]),
            })
            .collect();
        Self {
            surface: SurfaceBvh::new(triangles),
            shading: Shading::new(mesh, textures),
        }
    }

    pub fn triangle_count(&self) -> usize {
        self.triangles().len()
    }

    fn triangles(&self) -> &[Triangle] {
        self.surface.triangles()
    }

    /// Closest hit of the ray `origin + t·dir`, `t > 0`; `dir` need not be unit length.
    pub fn cast(&self, origin: Vec3, dir: Vec3) -> Option<Hit> {
        self.cast_within(origin, dir, f32::INFINITY)
    }

    /// Closest hit with `0 < t ≤ max_distance` (in units of `dir`).
    pub fn cast_within(&self, origin: Vec3, dir: Vec3, max_distance: f32) -> Option<Hit> {
        let hit = self.surface.first_hit(origin, dir, max_distance)?;
        let tri = &self.triangles()[hit.triangle as usize];
        let point = Vec3A::from(origin) + Vec3A::from(dir) * hit.t;
        Some(Hit {
            distance: hit.t,
            triangle: hit.triangle,
            barycentrics: barycentrics(tri, point),
        })
    }

    /// Geometric unit normal of a triangle (right-handed winding: counter-clockwise seen from the
    /// side it points to).
    pub fn triangle_normal(&self, triangle: u32) -> Vec3 {
        self.triangles()[triangle as usize].compute_normal().into()
    }

    /// Z-depth image of the view; pixel (x, y) looks along ((x−cx)/fx, (y−cy)/fy, 1) in camera
    /// coordinates. Misses are 0.
    pub fn depth_image(&self, world_from_camera: &Pose, k: &Intrinsics) -> DepthImage {
        let mut depth = DepthImage::new(k.width, k.height);
        depth
            .data
            .par_chunks_mut(k.width as usize)
            .enumerate()
            .for_each(|(y, row)| {
                for (x, z) in row.iter_mut().enumerate() {
                    let (origin, dir) = camera_ray(world_from_camera, k, x, y);
                    *z = self.cast(origin, dir).map_or(0.0, |h| h.distance);
                }
            });
        depth
    }

    /// Colour and z-depth of the view, shaded as the rasterizer's fragment shader does: textures
    /// filtered trilinearly at the level of detail the uv derivatives of the pixel's 2×2 quad give
    /// (see [`RayCaster::uv_derivatives`]); misses are black with depth 0.
    pub fn render(&self, world_from_camera: &Pose, k: &Intrinsics) -> RayCastFrame {
        let mut rgb = RgbImage::new(k.width, k.height);
        let mut depth = DepthImage::new(k.width, k.height);
        let mut triangles = vec![None; k.pixel_count()];
        let w = k.width as usize;
        rgb.data
            .par_chunks_mut(w * 3)
            .zip(depth.data.par_chunks_mut(w))
            .zip(triangles.par_chunks_mut(w))
            .enumerate()
            .for_each(|(y, ((rgb_row, depth_row), triangle_row))| {
                for x in 0..w {
                    let (origin, dir) = camera_ray(world_from_camera, k, x, y);
                    if let Some(hit) = self.cast(origin, dir) {
                        depth_row[x] = hit.distance;
                        triangle_row[x] = Some(hit.triangle);
                        let d = self.uv_derivatives(hit.triangle, world_from_camera, k, x, y);
                        rgb_row[x * 3..x * 3 + 3].copy_from_slice(&self.color_at(&hit, &d));
                    }
                }
            });
        RayCastFrame {
            rgb,
            depth,
            triangles,
        }
    }

    /// sRGB colour at a hit: vertex colour × texture (products in linear light), the texture
    /// filtered trilinearly at the level of detail `d` gives ([`UvDerivatives::ZERO`] = full
    /// resolution, bilinear).
    pub fn color_at(&self, hit: &Hit, d: &UvDerivatives) -> [u8; 3] {
        self.shading.color_at(hit, d)
    }

    /// The uv derivatives a GPU gives a fragment of `triangle` at pixel (x, y): differences of uv
    /// across the 2×2 pixel quad holding it, taken at the quad's top-left pixel (coarse
    /// derivatives, one level of detail per quad). uv is extrapolated over the triangle's plane
    /// where quad pixels see past it, as the GPU's helper invocations do; a quad ray parallel to
    /// the plane gives infinite derivatives (the coarsest level).
    pub fn uv_derivatives(
        &self,
        triangle: u32,
        world_from_camera: &Pose,
        k: &Intrinsics,
        x: usize,
        y: usize,
    ) -> UvDerivatives {
        let (x0, y0) = (x & !1, y & !1);
        let uv = |x: usize, y: usize| {
            let (origin, dir) = camera_ray(world_from_camera, k, x, y);
            self.plane_barycentrics(triangle, origin, dir)
                .map(|b| self.shading.uv(triangle, b))
        };
        match (uv(x0, y0), uv(x0 + 1, y0), uv(x0, y0 + 1)) {
            (Some(c), Some(r), Some(d)) => UvDerivatives {
                dx: [r[0] - c[0], r[1] - c[1]],
                dy: [d[0] - c[0], d[1] - c[1]],
            },
            _ => UvDerivatives {
                dx: [f32::INFINITY; 2],
                dy: [f32::INFINITY; 2],
            },
        }
    }

    /// Barycentric weights (unclamped) of the point where the line `origin + t·dir`, any t, meets
    /// the plane of `triangle`; `None` when it runs parallel to it.
    fn plane_barycentrics(&self, triangle: u32, origin: Vec3, dir: Vec3) -> Option<[f32; 3]> {
        let tri = &self.triangles()[triangle as usize];
        let n = (tri.v1 - tri.v0).cross(tri.v2 - tri.v0);
        let denom = n.dot(dir.into());
        if denom == 0.0 || !denom.is_finite() {
            return None;
        }
        let t = n.dot(tri.v0 - Vec3A::from(origin)) / denom;
        let b = plane_barycentrics(tri, Vec3A::from(origin) + Vec3A::from(dir) * t);
        b.iter().all(|w| w.is_finite()).then_some(b)
    }

    /// Texture layer a triangle samples.
    pub fn layer(&self, triangle: u32) -> u32 {
        self.shading.layer(triangle)
    }

    /// Per pixel of `frame`: whether its 3×3 neighbourhood sees a change of surface (hit against
    /// miss, another texture layer, or another plane: a crease, a step or another object).
    /// Colour may jump there, and an edge one pixel off between two renderers is not a shading
    /// error, so colour comparisons leave these pixels out.
    pub fn surface_edges(&self, frame: &RayCastFrame) -> Vec<bool> {
        let (w, h) = (frame.rgb.width as i64, frame.rgb.height as i64);
        let at =
            |x: i64, y: i64| frame.triangles[(y.clamp(0, h - 1) * w + x.clamp(0, w - 1)) as usize];
        let same = |a: Option<u32>, b: Option<u32>| match (a, b) {
            (None, None) => true,
            (Some(a), Some(b)) => {
                a == b || (self.layer(a) == self.layer(b) && self.same_plane(a, b))
            }
            _ => false,
        };
        (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                let centre = at(x, y);
                (-1..=1).any(|dy| (-1..=1).any(|dx| !same(centre, at(x + dx, y + dy))))
            })
            .collect()
    }

    fn same_plane(&self, a: u32, b: u32) -> bool {
        let triangles = self.triangles();
        let (ta, tb) = (&triangles[a as usize], &triangles[b as usize]);
        let (na, nb) = (ta.compute_normal(), tb.compute_normal());
        na.dot(nb) >= SAME_PLANE_COS
            && na.dot(tb.v0 - ta.v0).abs() <= SAME_PLANE_OFFSET
            && nb.dot(ta.v0 - tb.v0).abs() <= SAME_PLANE_OFFSET
    }

    /// The surface point nearest to `point` (`None` for an empty mesh).
    pub fn nearest_surface(&self, point: Vec3) -> Option<SurfacePoint> {
        self.surface.nearest(point)
    }
}

/// World-space origin and direction (z component 1 in camera coordinates) of pixel (x, y).
pub fn camera_ray(world_from_camera: &Pose, k: &Intrinsics, x: usize, y: usize) -> (Vec3, Vec3) {
    let d = DVec3::new((x as f64 - k.cx) / k.fx, (y as f64 - k.cy) / k.fy, 1.0);
    (
        world_from_camera.translation.as_vec3(),
        (world_from_camera.rotation * d).as_vec3(),
    )
}

/// Barycentric weights of a point inside the triangle (clamped onto it: hits may lie a little
/// outside, see [`SurfaceBvh::first_hit`]).
fn barycentrics(tri: &Triangle, p: Vec3A) -> [f32; 3] {
    let [_, b1, b2] = plane_barycentrics(tri, p);
    if !(b1.is_finite() && b2.is_finite()) {
        return [1.0, 0.0, 0.0];
    }
    let b1 = b1.clamp(0.0, 1.0);
    let b2 = b2.clamp(0.0, 1.0 - b1);
    [1.0 - b1 - b2, b1, b2]
}

/// Barycentric weights of a point in the triangle's plane, unclamped (non-finite for a
/// degenerate triangle).
fn plane_barycentrics(tri: &Triangle, p: Vec3A) -> [f32; 3] {
    let (e1, e2, ep) = (tri.v1 - tri.v0, tri.v2 - tri.v0, p - tri.v0);
    let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (dp1, dp2) = (ep.dot(e1), ep.dot(e2));
    let denom = d11 * d22 - d12 * d12;
    let b1 = (d22 * dp1 - d12 * dp2) / denom;
    let b2 = (d11 * dp2 - d12 * dp1) / denom;
    [1.0 - b1 - b2, b1, b2]
}

#[cfg(test)]
mod tests;
