//! Many runs at once: `<runs>/<method>/<sequence>.txt` estimates (or `<sequence>/<repeat>.txt`)
//! against the ground truth of `<datasets>/<sequence>/`, aggregated into the benchmark's tables.
//!
//! Sequence names carry the setting: `<scene>__<setting>` (`room0__fog-3`), a bare `<scene>` is
//! clean. A setting's category is its leading perturbation name (`fog-3-dynamic` → `fog`).
//! A run is failed when its runner left `<repeat>.failed` (or `<sequence>.failed`), a text file
//! whose first line is the reason, or when its estimate is missing, empty, unreadable or
//! unassociable. A `.failed` record wins over an estimate of the same name: that estimate is
//! stale and not evaluated. A failed run counts as ATE = the failure ATE (1.0 m by default);
//! SR, SR path ratio and tracked fraction 0; marked F.
//!
//! The report (`write_report`): Markdown, JSON, CSV, the CSR curves and per-category bars as
//! SVG and PNG, and `report.html`, all of it in one file with the figures inline.

mod category_bars;
mod collect;
mod csr_plot;
mod figures;
mod html;
mod layout;
mod naming;
mod summary;
mod tables;
mod welch;
mod write;

use std::path::{Path, PathBuf};

use rslam_core::trajectory_io::ReadOptions;
use serde::Serialize;

pub use collect::{collect_runs, CollectedRuns, RunRecord};
pub(crate) use layout::GROUND_TRUTH_FILES;
pub use layout::{
    find_estimates, find_methods, find_sequences, ground_truth_of, Estimate, Sequence, NO_REASON,
};
pub use naming::{category, scene_and_setting, CLEAN};
pub use summary::{
    csr, summarize, CategoryBound, CsrPoint, MeanAndMin, MethodSummary, RunsSummary, SettingCell,
    SettingTest, SurvivalBound, CSR_THRESHOLDS,
};
pub use welch::{welch_t_test, WelchTest};
pub use write::{csv_field, summary_text, write_report};

use crate::{EvalError, EvalOptions};

/// The benchmark's convention for the ATE of a failed run, metres.
pub const DEFAULT_FAILURE_ATE: f64 = 1.0;

#[derive(Clone, Debug, PartialEq)]
pub struct RunsOptions {
    pub runs_dir: PathBuf,
    pub datasets_dir: PathBuf,
    pub read: ReadOptions,
    pub eval: EvalOptions,
    pub failure_ate: f64,
    /// A folder inside `runs_dir` that is not a method (the report's own output).
    pub skip_dir: Option<PathBuf>,
}

/// Every run and the tables over them; serialises to `report.json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunsReport {
    pub summary: RunsSummary,
    pub runs: Vec<RunRecord>,
    pub unmatched: Vec<PathBuf>,
}

/// Evaluates every run and aggregates them.
pub fn evaluate_runs(options: &RunsOptions) -> Result<RunsReport, EvalError> {
    if !(options.failure_ate.is_finite() && options.failure_ate > 0.0) {
        return Err(EvalError::BadOption {
            name: "failure-ate",
            value: options.failure_ate.to_string(),
            expected: "a positive number of metres",
        });
    }
    let CollectedRuns { runs, unmatched } = collect_runs(options)?;
    Ok(RunsReport {
        summary: summarize(&runs, options.failure_ate),
        runs,
        unmatched,
    })
}

/// Evaluates every run and writes the report files into `out`; returns the report and the paths.
pub fn evaluate_runs_into(
    options: &RunsOptions,
    out: &Path,
) -> Result<(RunsReport, Vec<PathBuf>), EvalError> {
    let report = evaluate_runs(options)?;
    let written = write_report(&report, out)?;
    Ok((report, written))
}
