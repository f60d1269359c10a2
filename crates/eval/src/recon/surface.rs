//! One side of the comparison: the file read and checked, its BVH, the points sampled on it.

use std::path::Path;

use glam::Vec3;
use rslam_core::hash::{fnv1a64, splitmix64};
use rslam_core::mesh_io::{read_ply, MeshGeometry};
use rslam_core::SurfaceBvh;

use super::sampling::{sample_points, sample_triangles};
use super::{Culling, ReconOptions, SurfaceKind, SurfaceSummary};
use crate::EvalError;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Role {
    /// A mesh or a point cloud.
    Reconstruction,
    /// A mesh.
    GroundTruth,
}

impl Role {
    /// Keeps the two sides' draws independent under one seed.
    fn stream(self) -> u64 {
        fnv1a64(match self {
            Role::Reconstruction => b"reconstruction",
            Role::GroundTruth => b"ground truth",
        })
    }
}

pub(super) struct Surface {
    pub summary: SurfaceSummary,
    pub bvh: SurfaceBvh,
    pub samples: Vec<Vec3>,
}

impl Surface {
    /// Keeps the samples whose flag is set; an error when none is left.
    pub fn keep(&mut self, kept: &[bool], culling: Culling) -> Result<(), EvalError> {
        let mut flags = kept.iter();
        self.samples.retain(|_| *flags.next().unwrap_or(&false));
        self.summary.kept = self.samples.len();
        if self.samples.is_empty() {
            return Err(EvalError::BadMesh {
                path: self.summary.path.clone(),
                message: format!(
                    "no point of it lies in what the ground-truth cameras saw (culling {culling}): expected it in the scene's world frame, where the dataset's ground truth is"
                ),
            });
        }
        Ok(())
    }
}

pub(super) fn load_surface(
    path: &Path,
    role: Role,
    options: &ReconOptions,
) -> Result<Surface, EvalError> {
    let bad = |message: &str| EvalError::BadMesh {
        path: path.to_path_buf(),
        message: message.to_string(),
    };
    let is_ply = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ply"));
    if !is_ply && path.exists() {
        return Err(bad(
            "expected a .ply file (write other meshes as PLY with `rslam scene export FILE --out FILE.ply`)",
        ));
    }
    let geometry = read_ply(path)?;
    if geometry.positions.is_empty() {
        return Err(bad(match role {
            Role::Reconstruction => "no vertices: expected a mesh or a point cloud",
            Role::GroundTruth => "no vertices: expected the ground-truth mesh",
        }));
    }
    if role == Role::GroundTruth && geometry.is_point_cloud() {
        return Err(bad(
            "no faces: expected the ground-truth mesh (`rslam scene export` writes it)",
        ));
    }
    let key = splitmix64(options.seed ^ role.stream());
    let samples = if geometry.is_point_cloud() {
        sample_points(&geometry.positions, options.samples, key)
    } else {
        sample_triangles(&geometry, options.samples, key).ok_or_else(|| {
            bad("every triangle has zero area: expected a surface to sample points on")
        })?
    };
    Ok(Surface {
        summary: summary(path, &geometry, samples.len()),
        bvh: SurfaceBvh::of_geometry(&geometry),
        samples,
    })
}

fn summary(path: &Path, geometry: &MeshGeometry, samples: usize) -> SurfaceSummary {
    SurfaceSummary {
        path: path.to_path_buf(),
        kind: if geometry.is_point_cloud() {
            SurfaceKind::PointCloud
        } else {
            SurfaceKind::Mesh
        },
        vertices: geometry.positions.len(),
        triangles: geometry.triangle_count(),
        samples,
        kept: samples,
    }
}
