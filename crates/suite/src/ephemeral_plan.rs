//! What `suite bench --ephemeral` will need: disk for the frames of the `jobs` largest
//! sequences in flight, plus what every sequence keeps (manifest, checksums, ground truth), plus
//! what the runs keep (estimates, logs, meshes); and time: the frames still to draw and the
//! methods' runs, `jobs` at once. The runs' figures are measured from this suite's finished runs
//! when there are any, else estimated (said so).

use std::collections::BTreeSet;

use serde::Serialize;

use crate::bench::{recorded_runs, RUNS_DIR};
use crate::disk::folder_bytes;
use crate::plan::SuitePlan;
use crate::{Suite, SuiteError};

/// A run keeps its TUM estimate (about 90 bytes a line) and its log: assumed 150 bytes a frame
/// per run until runs are measured.
const ASSUMED_RUN_BYTES_PER_FRAME: u64 = 150;

#[derive(Clone, Debug, Serialize)]
pub struct EphemeralPlan {
    /// Sequences in flight.
    pub jobs: usize,
    /// The frames of the `jobs` largest sequences.
    pub bytes_in_flight: u64,
    /// What every sequence keeps once its frames are deleted.
    pub bytes_kept: u64,
    /// What the runs keep, for the whole suite.
    pub bytes_runs: u64,
    pub bytes_total: u64,
    /// Where `bytes_runs` and the run time come from.
    pub runs_source: String,
    /// The methods' run time still to go, `jobs` at once; `None` before any run is timed.
    pub run_seconds_to_go: Option<f64>,
    /// Frames to draw and runs to go.
    pub seconds_to_go: f64,
}

/// The ephemeral plan of `suite` beside its plan `plan` (of the same sequences).
pub fn plan_ephemeral(
    suite: &Suite,
    plan: &SuitePlan,
    jobs: usize,
) -> Result<EphemeralPlan, SuiteError> {
    let jobs = jobs.max(1);
    let mut sizes: Vec<u64> = plan.sequences.iter().map(|s| s.bytes).collect();
    sizes.sort_unstable_by(|a, b| b.cmp(a));
    let bytes_in_flight = sizes.iter().take(jobs).sum();
    let bytes_kept = plan.sequences.iter().map(|s| s.kept_bytes).sum();
    let frames_of = |name: &str| {
        plan.sequences
            .iter()
            .find(|s| s.name == name)
            .map_or(0, |s| s.frames_written)
    };
    let records = recorded_runs(suite);
    let with_runs: BTreeSet<&str> = records.iter().map(|(s, _)| s.name.as_str()).collect();
    let all_frames: usize = plan.sequences.iter().map(|s| s.frames_written).sum();
    let (bytes_runs, runs_source, run_seconds_to_go) = if records.is_empty() {
        (
            ASSUMED_RUN_BYTES_PER_FRAME * all_frames as u64,
            format!(
                "no run finished yet: one run a sequence assumed, {ASSUMED_RUN_BYTES_PER_FRAME} B a frame (estimate and log); the methods' time comes on top"
            ),
            None,
        )
    } else {
        let run_frames: usize = records.iter().map(|(s, _)| frames_of(&s.name)).sum();
        let seconds: f64 = records.iter().map(|(_, r)| r.seconds).sum();
        let runs_bytes = folder_bytes(&suite.dir.join(RUNS_DIR))?;
        let frames_with_runs: usize = with_runs.iter().map(|n| frames_of(n)).sum();
        let scale = all_frames as f64 / frames_with_runs.max(1) as f64;
        let frames_without_runs: usize = plan
            .sequences
            .iter()
            .filter(|s| !with_runs.contains(s.name.as_str()))
            .map(|s| s.frames_written)
            .sum();
        let runs_per_frame = run_frames as f64 / frames_with_runs.max(1) as f64;
        let seconds_per_run_frame = seconds / run_frames.max(1) as f64;
        (
            (runs_bytes as f64 * scale).round() as u64,
            format!(
                "measured over {} finished run(s) on {} sequence(s) of this suite",
                records.len(),
                with_runs.len()
            ),
            Some(frames_without_runs as f64 * runs_per_frame * seconds_per_run_frame / jobs as f64),
        )
    };
    Ok(EphemeralPlan {
        jobs,
        bytes_in_flight,
        bytes_kept,
        bytes_runs,
        bytes_total: bytes_in_flight + bytes_kept + bytes_runs,
        runs_source,
        seconds_to_go: plan.seconds_to_go + run_seconds_to_go.unwrap_or(0.0),
        run_seconds_to_go,
    })
}
