//! The trajectory panel's data: the ground truth of the shown frames and, with `--estimate`, the
//! estimate aligned to it by `rslam-eval` (the same numbers `rslam eval` prints), per pose.

use std::path::{Path, PathBuf};

use rslam_core::trajectory_io::read_trajectory;
use rslam_core::{nearest_time, Pose, Trajectory};
use rslam_eval::{associate, evaluate, EvalOptions};

use crate::ViewerError;
use glam::DVec3;

/// An estimate aligned to the ground truth, with each associated pose's error.
#[derive(Clone, Debug, PartialEq)]
pub struct EstimateOverlay {
    pub path: PathBuf,
    /// ATE RMSE, metres.
    pub ate_rmse: f64,
    /// Associated pairs: the estimate's position aligned into the ground-truth frame, its error.
    pub aligned: Vec<DVec3>,
    pub errors: Vec<f64>,
    pub max_error: f64,
}

impl EstimateOverlay {
    /// Reads the estimate at `path` and aligns it to `ground_truth` (SE(3), evo's defaults).
    pub fn new(path: &Path, ground_truth: &Trajectory) -> Result<Self, ViewerError> {
        let estimate = read_trajectory(path, None)?.trajectory;
        let wrap = |source| ViewerError::Eval {
            path: path.to_path_buf(),
            source,
        };
        let options = EvalOptions::default();
        let evaluation = evaluate(&estimate, ground_truth, &options).map_err(wrap)?;
        let association = associate(&estimate, ground_truth, &options.matching).map_err(wrap)?;
        let aligned: Vec<DVec3> = association
            .est_indices
            .iter()
            .map(|&i| evaluation.alignment.apply(estimate.poses[i].translation))
            .collect();
        let errors = evaluation.series.ate_errors.clone();
        Ok(Self {
            path: path.to_path_buf(),
            ate_rmse: evaluation.ate.rmse,
            max_error: evaluation.ate.max,
            aligned,
            errors,
        })
    }
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct TrajectoryView {
    pub ground_truth: Trajectory,
    pub estimate: Option<EstimateOverlay>,
}

impl TrajectoryView {
    /// The ground-truth pose of the frame captured at `time`, within `max_diff` seconds.
    pub fn pose_at(&self, time: f64, max_diff: f64) -> Option<Pose> {
        let gt = &self.ground_truth;
        nearest_time(gt.timestamps.iter().copied(), time, max_diff).map(|i| gt.poses[i])
    }
}
