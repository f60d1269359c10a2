//! Which part of each surface the mapping metrics are taken over: the points some ground-truth
//! camera had in view (`frustum`, NICE-SLAM's and Co-SLAM's culling) and, of those, the points it
//! actually saw past the ground-truth mesh (`visible`, Co-SLAM's occlusion culling, applied to
//! the ground truth as well so that completion measures the observed surface).
//!
//! A point is in a view's frustum when it lies in front of the camera, no farther than the
//! camera's depth files can encode, and projects inside the image (pixel centres 0..=W−1 and
//! 0..=H−1, as Co-SLAM's `cull_from_one_pose`). It is visible from that view when the segment
//! from the camera centre to it meets the ground-truth mesh nowhere nearer than
//! [`OCCLUSION_TOLERANCE_M`] of z-depth in front of it (Co-SLAM compares with the rendered depth
//! plus 2 cm); the mesh is the scene's, never the dataset's depth, which may be perturbed.

use std::fmt;
use std::str::FromStr;

use glam::{DMat3, DVec3, Vec3};
use rayon::prelude::*;
use rslam_core::dataset::DatasetViews;
use rslam_core::SurfaceBvh;
use serde::Serialize;

/// How much nearer than a point the ground-truth mesh may be, in z-depth, before it hides it.
pub const OCCLUSION_TOLERANCE_M: f64 = 0.02;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Culling {
    /// Every sampled point counts.
    None,
    /// Points inside at least one ground-truth camera's view frustum.
    Frustum,
    /// Points some ground-truth camera saw, unoccluded by the ground-truth mesh (the default).
    #[default]
    Visible,
}

impl Culling {
    pub const ALL: [Culling; 3] = [Culling::None, Culling::Frustum, Culling::Visible];

    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Frustum => "frustum",
            Self::Visible => "visible",
        }
    }
}

impl fmt::Display for Culling {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Culling {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or_else(|| format!("unknown culling '{s}': expected none, frustum or visible"))
    }
}

/// One view, ready to test points against.
struct ViewTest {
    camera_from_world: DMat3,
    centre: DVec3,
    fx: f64,
    fy: f64,
    cx: f64,
    cy: f64,
    max_u: f64,
    max_v: f64,
    max_depth: f64,
}

impl ViewTest {
    /// The point's z-depth when it lies in the frustum.
    fn depth_in_frustum(&self, p: DVec3) -> Option<f64> {
        let c = self.camera_from_world * (p - self.centre);
        if !(c.z > 0.0 && c.z <= self.max_depth) {
            return None;
        }
        let u = self.fx * c.x / c.z + self.cx;
        let v = self.fy * c.y / c.z + self.cy;
        ((0.0..=self.max_u).contains(&u) && (0.0..=self.max_v).contains(&v)).then_some(c.z)
    }

    /// Cast from the point towards the camera (t = 1 at the camera centre): occluders near the
    /// point (the front of the object whose back it is on) end the search soonest. At t, the
    /// segment is (1 − t)·depth from the camera, so t > tolerance / depth is nearer than the
    /// point by more than the tolerance.
    fn sees(&self, p: DVec3, depth: f64, occluders: &SurfaceBvh) -> bool {
        let min_t = OCCLUSION_TOLERANCE_M / depth;
        min_t >= 1.0
            || !occluders.is_blocked(p.as_vec3(), (self.centre - p).as_vec3(), min_t as f32, 1.0)
    }
}

/// Per point: whether the culling keeps it (all `true` for [`Culling::None`]).
pub(super) fn kept(
    points: &[Vec3],
    culling: Culling,
    views: &DatasetViews,
    ground_truth: &SurfaceBvh,
) -> Vec<bool> {
    if culling == Culling::None {
        return vec![true; points.len()];
    }
    let tests: Vec<ViewTest> = views
        .views
        .iter()
        .map(|view| {
            let camera = &views.cameras[view.camera];
            let k = &camera.intrinsics;
            let pose = &view.world_from_camera;
            ViewTest {
                camera_from_world: DMat3::from_quat(pose.rotation.inverse()),
                centre: pose.translation,
                fx: k.fx,
                fy: k.fy,
                cx: k.cx,
                cy: k.cy,
                max_u: k.width as f64 - 1.0,
                max_v: k.height as f64 - 1.0,
                max_depth: camera.max_depth_m.unwrap_or(f64::INFINITY),
            }
        })
        .collect();
    points
        .par_iter()
        .map(|p| {
            let p = p.as_dvec3();
            tests.iter().any(|t| {
                t.depth_in_frustum(p).is_some_and(|depth| {
                    culling == Culling::Frustum || t.sees(p, depth, ground_truth)
                })
            })
        })
        .collect()
}
