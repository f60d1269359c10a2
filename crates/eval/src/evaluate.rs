//! One estimate against its ground truth: association → alignment → ATE, RPE, SR.

use std::path::Path;

use glam::DVec3;
use rslam_core::trajectory_io::{read_trajectory_with, ReadOptions, TimeSource, TrajectoryFile};
use rslam_core::{Pose, Trajectory};
use serde::Serialize;

use crate::alignment::{fit_alignment, AlignMode, Similarity};
use crate::association::{associate, Matching};
use crate::rpe::{relative_pose_errors, RpeOptions};
use crate::statistics::ErrorStatistics;
use crate::success_rate::{success_rate, SuccessRate};
use crate::EvalError;

/// How to evaluate: evo's defaults are `Matching::default()` (0.01 s), SE(3) alignment and RPE
/// over consecutive frame pairs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct EvalOptions {
    pub matching: Matching,
    pub align: AlignMode,
    pub rpe: RpeOptions,
}

/// The result of one evaluation; serialises to the `rslam eval --json` object.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Evaluation {
    /// Absolute trajectory error (m) after alignment.
    pub ate: ErrorStatistics,
    /// RPE translation part (m).
    pub rpe_trans: ErrorStatistics,
    /// RPE rotation angle (degrees).
    pub rpe_rot_deg: ErrorStatistics,
    /// SR, the SR path ratio, the tracked fraction and the path lengths behind them; their
    /// fields sit at the top level of the JSON object.
    #[serde(flatten)]
    pub success_rate: SuccessRate,
    /// Associated pose pairs.
    pub pairs: usize,
    /// Estimate-to-ground-truth alignment (identity for `none`; scale 1 unless `sim3`).
    pub alignment: Similarity,
    /// The most pairs there could be (poses of the shorter trajectory).
    pub max_pairs: usize,
    pub options: EvalOptions,
    #[serde(skip)]
    pub series: EvalSeries,
}

/// Per-pose data behind the statistics, for plots.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EvalSeries {
    /// Every ground-truth position.
    pub gt_positions: Vec<DVec3>,
    /// Every estimate position, aligned into the ground-truth frame.
    pub est_positions: Vec<DVec3>,
    /// Estimate time of each associated pair, seconds since the first pair.
    pub pair_times: Vec<f64>,
    /// ATE of each associated pair, metres.
    pub ate_errors: Vec<f64>,
    /// The ground-truth pose of each associated pair.
    pub pair_gt_indices: Vec<usize>,
}

/// Evaluates `est` against `gt`. Errors: no association, degenerate alignment, no RPE pair.
pub fn evaluate(
    est: &Trajectory,
    gt: &Trajectory,
    options: &EvalOptions,
) -> Result<Evaluation, EvalError> {
    let association = associate(est, gt, &options.matching)?;
    let est_poses: Vec<Pose> = association
        .est_indices
        .iter()
        .map(|&i| est.poses[i])
        .collect();
    let gt_poses: Vec<Pose> = association
        .gt_indices
        .iter()
        .map(|&i| gt.poses[i])
        .collect();
    let est_positions: Vec<DVec3> = est_poses.iter().map(|p| p.translation).collect();
    let gt_positions: Vec<DVec3> = gt_poses.iter().map(|p| p.translation).collect();

    let alignment = fit_alignment(options.align, &est_positions, &gt_positions)?;
    let aligned: Vec<Pose> = est_poses
        .iter()
        .map(|p| alignment.apply_to_pose(p))
        .collect();
    let ate_errors: Vec<f64> = aligned
        .iter()
        .zip(&gt_positions)
        .map(|(e, g)| (e.translation - *g).length())
        .collect();
    let rpe = relative_pose_errors(&gt_poses, &aligned, &options.rpe)?;
    let success_rate = success_rate(est, gt, &options.matching, alignment.scale);

    let stats = |errors: &[f64]| {
        ErrorStatistics::of(errors).expect("association and RPE pairs are non-empty")
    };
    let first_time = est.timestamps[association.est_indices[0]];
    Ok(Evaluation {
        ate: stats(&ate_errors),
        rpe_trans: stats(&rpe.translation),
        rpe_rot_deg: stats(&rpe.rotation_deg),
        success_rate,
        pairs: association.len(),
        alignment,
        max_pairs: association.max_pairs,
        options: *options,
        series: EvalSeries {
            gt_positions: gt.poses.iter().map(|p| p.translation).collect(),
            est_positions: est
                .poses
                .iter()
                .map(|p| alignment.apply(p.translation))
                .collect(),
            pair_times: association
                .est_indices
                .iter()
                .map(|&i| est.timestamps[i] - first_time)
                .collect(),
            ate_errors,
            pair_gt_indices: association.gt_indices.clone(),
        },
    })
}

/// Evaluates two trajectories as read from their files. When either has no timestamps (KITTI
/// without a times file), poses are matched by index whatever `options.matching` says.
pub fn evaluate_files(
    est: &TrajectoryFile,
    gt: &TrajectoryFile,
    options: &EvalOptions,
) -> Result<Evaluation, EvalError> {
    let untimed = |t: TimeSource| t == TimeSource::FrameIndex;
    let mut options = *options;
    if untimed(est.time_source) || untimed(gt.time_source) {
        options.matching = Matching::Index;
    }
    evaluate(&est.trajectory, &gt.trajectory, &options)
}

/// Reads both files (see [`read_trajectory_with`]) and evaluates them with [`evaluate_files`].
pub fn read_and_evaluate(
    est_path: &Path,
    gt_path: &Path,
    read: &ReadOptions,
    options: &EvalOptions,
) -> Result<Evaluation, EvalError> {
    let est = read_trajectory_with(est_path, read)?;
    let gt = read_trajectory_with(gt_path, read)?;
    evaluate_files(&est, &gt, options)
}
