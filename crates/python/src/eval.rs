//! `rslam.eval`: one estimate against its ground truth with `rslam_eval::evaluate_files`, the
//! function behind `rslam eval EST GT`; the result is the `rslam eval --json` object.

use std::path::PathBuf;

use crate::render::pose_of_matrix;
use glam::{DQuat, DVec3};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use rslam_core::trajectory_io::{
    read_trajectory_with, ReadOptions, TimeSource, TrajectoryFile, TrajectoryFormat,
};
use rslam_core::{Pose, Trajectory};
use rslam_eval::{evaluate_files, AlignMode, DeltaUnit, EvalOptions, Matching, RpeOptions};

fn parse<T: std::str::FromStr>(what: &str, text: &str) -> PyResult<T>
where
    T::Err: std::fmt::Display,
{
    text.parse::<T>()
        .map_err(|e| PyValueError::new_err(format!("{what}: {e}")))
}

/// A trajectory from a path, an Nx8 array of TUM rows (t tx ty tz qx qy qz qw) or Nx4x4
/// camera-to-world matrices (no timestamps: matched by index, as KITTI files are).
fn trajectory(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    what: &str,
    read: &ReadOptions,
) -> PyResult<TrajectoryFile> {
    if let Ok(path) = obj.extract::<PathBuf>() {
        return py
            .detach(|| read_trajectory_with(&path, read))
            .map_err(crate::errors::core);
    }
    if let Ok(rows) = obj.extract::<Vec<[f64; 8]>>() {
        let mut timestamps = Vec::with_capacity(rows.len());
        let mut poses = Vec::with_capacity(rows.len());
        for (i, r) in rows.iter().enumerate() {
            let q = DQuat::from_xyzw(r[4], r[5], r[6], r[7]);
            if q.length() == 0.0 || r.iter().any(|v| !v.is_finite()) {
                return Err(PyValueError::new_err(format!(
                    "{what}: row {i}: expected finite t tx ty tz qx qy qz qw with a non-zero \
                     quaternion"
                )));
            }
            timestamps.push(r[0]);
            poses.push(Pose::new(q / q.length(), DVec3::new(r[1], r[2], r[3])));
        }
        return Ok(TrajectoryFile {
            format: TrajectoryFormat::Tum,
            time_source: TimeSource::File,
            trajectory: Trajectory::new(timestamps, poses),
        });
    }
    if let Ok(matrices) = obj.extract::<Vec<[[f64; 4]; 4]>>() {
        let poses: Vec<Pose> = matrices.iter().map(pose_of_matrix).collect();
        return Ok(TrajectoryFile {
            format: TrajectoryFormat::Replica,
            time_source: TimeSource::FrameIndex,
            trajectory: Trajectory::new((0..poses.len()).map(|i| i as f64).collect(), poses),
        });
    }
    Err(PyTypeError::new_err(format!(
        "{what}: expected a trajectory file path, an Nx8 array (t tx ty tz qx qy qz qw) or an \
         Nx4x4 array of camera-to-world matrices"
    )))
}

/// The `rslam eval --json` object for `est` against `gt`, as JSON text.
#[pyfunction]
#[pyo3(signature = (est, gt, align = "se3", max_diff = rslam_eval::DEFAULT_MAX_DIFF, t_offset = 0.0,
    format = None, rate = ReadOptions::DEFAULT_REPLICA_RATE_HZ, delta = 1.0, delta_unit = "f",
    all_pairs = false, est_topic = None, gt_topic = None))]
#[allow(clippy::too_many_arguments)]
pub fn evaluate_json(
    py: Python<'_>,
    est: &Bound<'_, PyAny>,
    gt: &Bound<'_, PyAny>,
    align: &str,
    max_diff: f64,
    t_offset: f64,
    format: Option<&str>,
    rate: f64,
    delta: f64,
    delta_unit: &str,
    all_pairs: bool,
    est_topic: Option<String>,
    gt_topic: Option<String>,
) -> PyResult<String> {
    let read = ReadOptions {
        format: format.map(|f| parse("format", f)).transpose()?,
        replica_rate_hz: rate,
        kitti_times: None,
        topic: None,
        dataparser_transforms: None,
    };
    let with_topic = |topic: Option<String>| ReadOptions {
        topic,
        ..read.clone()
    };
    let options = EvalOptions {
        matching: Matching::Time { max_diff, t_offset },
        align: parse::<AlignMode>("align", align)?,
        rpe: RpeOptions {
            delta,
            delta_unit: parse::<DeltaUnit>("delta_unit", delta_unit)?,
            all_pairs,
        },
    };
    let est = trajectory(py, est, "est", &with_topic(est_topic))?;
    let gt = trajectory(py, gt, "gt", &with_topic(gt_topic))?;
    let evaluation = py
        .detach(|| evaluate_files(&est, &gt, &options))
        .map_err(crate::errors::eval)?;
    serde_json::to_string(&evaluation).map_err(|e| PyValueError::new_err(e.to_string()))
}
