//! `rslam suite bench`: every method on every complete sequence of a shard, each repeat once,
//! resumably; results where `rslam eval --runs` reads them (`runs/<method>/<sequence>/<repeat>.txt`,
//! failures as `<repeat>.failed`).

mod ephemeral;
mod measured_csv;
mod method;
mod process;
mod reconstruction;
mod record;
mod rendered_views;
mod run_method;

pub use ephemeral::{bench_ephemeral, EphemeralOptions, EphemeralOutcome, EphemeralSummary};
pub use method::{Method, RunPlaces, PLACEHOLDERS};
pub use process::{run_process, Ending, ProcessReport};
pub use reconstruction::{report_reconstructions, ReconRow};
pub use record::{recorded_runs, succeeded_runs, RunFiles, RunRecord, RUNS_DIR};
pub use rendered_views::{
    ate_correlations, report_rendered_views, AteCorrelation, RenderedViewRow, ViewQuality,
    CLEAN_DIR,
};
pub use run_method::{bench_suite, BenchOptions, BenchProgress, BenchSummary, RunId};
