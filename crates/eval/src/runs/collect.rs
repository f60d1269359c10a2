//! Evaluating every (method, sequence, repeat) run; a run that cannot be evaluated is a failure.

use std::collections::HashSet;
use std::path::PathBuf;

use rslam_core::trajectory_io::{read_trajectory_with, TrajectoryFile};
use serde::Serialize;

use super::layout::{find_estimates, find_methods, find_sequences, find_unmatched, Sequence};
use super::RunsOptions;
use crate::{evaluate_files, EvalError};

/// One run's result. A failed run tracked nothing: it carries the failure ATE, 0 for SR, SR path
/// ratio and tracked fraction, and the reason.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunRecord {
    pub method: String,
    pub sequence: String,
    pub scene: String,
    pub setting: String,
    /// Repeat name (file stem inside `<sequence>/`); `None` for `<sequence>.txt`.
    pub repeat: Option<String>,
    /// ATE rmse in metres, or the failure ATE.
    pub ate: f64,
    /// Covered fraction of the ground-truth path; `None` when the ground truth does not move.
    pub sr: Option<f64>,
    /// The paper's SR formula, L_est / L_gt; `None` when the ground truth does not move.
    pub sr_path_ratio: Option<f64>,
    /// Ground-truth poses paired with an estimate pose / ground-truth poses.
    pub tracked_fraction: f64,
    pub rpe_trans: Option<f64>,
    pub rpe_rot_deg: Option<f64>,
    pub pairs: Option<usize>,
    /// Why the run failed (the reason of its `.failed` record, missing or unreadable estimate,
    /// no association, …).
    pub failure: Option<String>,
}

impl RunRecord {
    pub fn failed(&self) -> bool {
        self.failure.is_some()
    }
}

/// Every run, and the estimate files that matched no dataset sequence.
#[derive(Clone, Debug, PartialEq)]
pub struct CollectedRuns {
    pub runs: Vec<RunRecord>,
    pub unmatched: Vec<PathBuf>,
}

/// Evaluates every method on every sequence of the datasets folder. A broken ground truth is an
/// error; a missing or broken estimate, or a `.failed` record, is a failed run.
pub fn collect_runs(options: &RunsOptions) -> Result<CollectedRuns, EvalError> {
    let sequences = find_sequences(&options.datasets_dir)?;
    let methods = find_methods(&options.runs_dir, options.skip_dir.as_deref())?;
    let names: HashSet<&str> = sequences.iter().map(|s| s.name.as_str()).collect();
    let mut runs = Vec::new();
    let mut unmatched = Vec::new();
    for sequence in &sequences {
        let gt = read_trajectory_with(&sequence.ground_truth, &options.read)?;
        for (method, dir) in &methods {
            let estimates = find_estimates(dir, &sequence.name)?;
            if estimates.is_empty() {
                let missing = dir.join(format!("{}.txt", sequence.name));
                let reason = format!("{}: no estimate", missing.display());
                runs.push(failed_run(
                    method,
                    sequence,
                    None,
                    reason,
                    options.failure_ate,
                ));
            }
            for estimate in estimates {
                if let Some(reason) = estimate.failure {
                    runs.push(failed_run(
                        method,
                        sequence,
                        estimate.repeat,
                        reason,
                        options.failure_ate,
                    ));
                    continue;
                }
                let outcome = read_trajectory_with(&estimate.path, &options.read)
                    .map_err(EvalError::from)
                    .and_then(|est: TrajectoryFile| evaluate_files(&est, &gt, &options.eval));
                runs.push(match outcome {
                    Ok(e) => RunRecord {
                        ate: e.ate.rmse,
                        sr: e.success_rate.sr,
                        sr_path_ratio: e.success_rate.sr_path_ratio,
                        tracked_fraction: e.success_rate.tracked_fraction,
                        rpe_trans: Some(e.rpe_trans.rmse),
                        rpe_rot_deg: Some(e.rpe_rot_deg.rmse),
                        pairs: Some(e.pairs),
                        failure: None,
                        ..identity(method, sequence, estimate.repeat)
                    },
                    Err(err) => {
                        let reason = match err {
                            EvalError::Core(_) => err.to_string(),
                            _ => format!("{}: {err}", estimate.path.display()),
                        };
                        failed_run(
                            method,
                            sequence,
                            estimate.repeat,
                            reason,
                            options.failure_ate,
                        )
                    }
                });
            }
        }
    }
    for (_, dir) in &methods {
        unmatched.extend(find_unmatched(dir, &names)?);
    }
    Ok(CollectedRuns { runs, unmatched })
}

fn identity(method: &str, sequence: &Sequence, repeat: Option<String>) -> RunRecord {
    RunRecord {
        method: method.to_string(),
        sequence: sequence.name.clone(),
        scene: sequence.scene.clone(),
        setting: sequence.setting.clone(),
        repeat,
        ate: f64::NAN,
        sr: None,
        sr_path_ratio: None,
        tracked_fraction: f64::NAN,
        rpe_trans: None,
        rpe_rot_deg: None,
        pairs: None,
        failure: None,
    }
}

fn failed_run(
    method: &str,
    sequence: &Sequence,
    repeat: Option<String>,
    reason: String,
    failure_ate: f64,
) -> RunRecord {
    RunRecord {
        ate: failure_ate,
        sr: Some(0.0),
        sr_path_ratio: Some(0.0),
        tracked_fraction: 0.0,
        failure: Some(reason),
        ..identity(method, sequence, repeat)
    }
}
