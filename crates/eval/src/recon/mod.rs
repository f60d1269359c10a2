//! Mapping metrics of a reconstruction against the ground-truth mesh, with the CO-SLAM protocol's
//! definitions: points sampled on both surfaces, then
//! accuracy = mean over the reconstruction's points of the distance to the ground truth,
//! completion = mean over the ground truth's points of the distance to the reconstruction,
//! completion ratio = share of the ground truth's points closer than a threshold (5 cm).
//!
//! Distances are to the other side's surface (point to nearest triangle, through a BVH), not to
//! the other side's sampled points as in CO-SLAM's KD-tree code: a mesh against itself gives 0,
//! and the number does not carry the sampling spacing of the other side. A reconstruction that is
//! a point cloud is measured to its nearest point (all of its points) and its accuracy is taken
//! over its points, subsampled to the sample count.
//!
//! Both sides are culled to what the ground-truth cameras saw before the means are taken
//! ([`Culling`], by default Co-SLAM's frustum and occlusion culling); the distances still go to
//! the other side's whole surface.

mod culling;
mod sampling;
mod surface;
mod text_report;

#[cfg(test)]
mod culling_tests;
#[cfg(test)]
mod tests;

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use rslam_core::dataset::DatasetViews;
use rslam_core::SurfaceBvh;
use serde::Serialize;

use crate::EvalError;
pub use culling::{Culling, OCCLUSION_TOLERANCE_M};
use surface::{load_surface, Role, Surface};
pub use text_report::recon_text_report;

/// The CO-SLAM protocol's sample count on each side.
pub const DEFAULT_RECON_SAMPLES: usize = 200_000;
/// The completion ratio's threshold of the CO-SLAM protocol, cm.
pub const DEFAULT_THRESHOLD_CM: f64 = 5.0;

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReconOptions {
    /// Points sampled on each surface (a point cloud with more points is subsampled).
    pub samples: usize,
    /// Picks the sampled points; draw i depends only on the seed and i, not on threading.
    pub seed: u64,
    /// A ground-truth point counts as completed when closer than this to the reconstruction, cm.
    pub threshold_cm: f64,
    /// The part of both surfaces measured.
    pub culling: Culling,
}

impl Default for ReconOptions {
    fn default() -> Self {
        Self {
            samples: DEFAULT_RECON_SAMPLES,
            seed: 0,
            threshold_cm: DEFAULT_THRESHOLD_CM,
            culling: Culling::default(),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceKind {
    Mesh,
    PointCloud,
}

/// What was read from one file and how many points were sampled on it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SurfaceSummary {
    pub path: PathBuf,
    pub kind: SurfaceKind,
    pub vertices: usize,
    pub triangles: usize,
    pub samples: usize,
    /// The samples the culling kept: the metrics are means over these.
    pub kept: usize,
}

impl SurfaceSummary {
    pub fn kept_percent(&self) -> f64 {
        self.kept as f64 / self.samples as f64 * 100.0
    }
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReconMetrics {
    /// Mean distance of the reconstruction's points to the ground-truth surface, cm.
    pub accuracy_cm: f64,
    /// Mean distance of the ground truth's points to the reconstruction, cm.
    pub completion_cm: f64,
    /// Ground-truth points closer than `options.threshold_cm` to the reconstruction, %.
    pub completion_ratio_percent: f64,
    pub options: ReconOptions,
    /// The ground-truth camera poses culled to (0 without culling).
    pub views: usize,
    pub reconstruction: SurfaceSummary,
    pub ground_truth: SurfaceSummary,
}

/// Reads the reconstruction (PLY mesh or point cloud) and the ground-truth mesh (PLY), both in
/// metres and in the scene's world frame, and measures one against the other over what the
/// dataset's `views` saw (needed unless the culling is [`Culling::None`]).
pub fn evaluate_reconstruction(
    reconstruction: &Path,
    ground_truth: &Path,
    options: &ReconOptions,
    views: Option<&DatasetViews>,
) -> Result<ReconMetrics, EvalError> {
    GroundTruthSurface::prepare(ground_truth, options, views)?.evaluate(reconstruction)
}

/// The ground-truth side read, sampled and culled once, for measuring many reconstructions of
/// one sequence against it.
pub struct GroundTruthSurface<'a> {
    surface: Surface,
    options: ReconOptions,
    views: Option<&'a DatasetViews>,
}

impl<'a> GroundTruthSurface<'a> {
    /// Reads the ground-truth mesh and culls its samples to what `views` saw (see
    /// [`evaluate_reconstruction`]).
    pub fn prepare(
        ground_truth: &Path,
        options: &ReconOptions,
        views: Option<&'a DatasetViews>,
    ) -> Result<Self, EvalError> {
        check(options)?;
        let views =
            match (options.culling, views) {
                (Culling::None, _) => None,
                (_, Some(views)) if !views.views.is_empty() => Some(views),
                (culling, _) => return Err(EvalError::BadOption {
                    name: "culling",
                    value: culling.to_string(),
                    expected:
                        "the ground-truth cameras of the dataset (--dataset DIR), or culling none",
                }),
            };
        let mut surface = load_surface(ground_truth, Role::GroundTruth, options)?;
        if let Some(views) = views {
            let kept = culling::kept(&surface.samples, options.culling, views, &surface.bvh);
            surface.keep(&kept, options.culling)?;
        }
        Ok(Self {
            surface,
            options: options.clone(),
            views,
        })
    }

    /// Measures the reconstruction (PLY mesh or point cloud) against this ground truth.
    pub fn evaluate(&self, reconstruction: &Path) -> Result<ReconMetrics, EvalError> {
        let (options, gt) = (&self.options, &self.surface);
        let mut rec = load_surface(reconstruction, Role::Reconstruction, options)?;
        if let Some(views) = self.views {
            let kept = culling::kept(&rec.samples, options.culling, views, &gt.bvh);
            rec.keep(&kept, options.culling)?;
        }
        let to_gt = distances(&rec.samples, &gt.bvh);
        let to_rec = distances(&gt.samples, &rec.bvh);
        let threshold_m = options.threshold_cm / 100.0;
        let completed = to_rec.iter().filter(|&&d| (d as f64) < threshold_m).count();
        Ok(ReconMetrics {
            accuracy_cm: mean(&to_gt) * 100.0,
            completion_cm: mean(&to_rec) * 100.0,
            completion_ratio_percent: completed as f64 / to_rec.len() as f64 * 100.0,
            options: options.clone(),
            views: self.views.map_or(0, |v| v.views.len()),
            reconstruction: rec.summary,
            ground_truth: gt.summary.clone(),
        })
    }
}

fn check(options: &ReconOptions) -> Result<(), EvalError> {
    if options.samples == 0 {
        return Err(EvalError::BadOption {
            name: "samples",
            value: "0".into(),
            expected: "at least 1 point per surface",
        });
    }
    if !(options.threshold_cm.is_finite() && options.threshold_cm > 0.0) {
        return Err(EvalError::BadOption {
            name: "threshold_cm",
            value: options.threshold_cm.to_string(),
            expected: "a positive distance in cm",
        });
    }
    Ok(())
}

/// Distance of each point to the surface, metres, in the order of `points`.
fn distances(points: &[glam::Vec3], surface: &SurfaceBvh) -> Vec<f32> {
    points
        .par_iter()
        .map(|&p| surface.nearest(p).map_or(f32::INFINITY, |s| s.distance))
        .collect()
}

fn mean(values: &[f32]) -> f64 {
    values.iter().map(|&v| v as f64).sum::<f64>() / values.len() as f64
}
