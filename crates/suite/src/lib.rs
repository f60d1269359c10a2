//! The benchmark matrix: a suite file lists sequences (`<scene>__<setting>`: a scene, a
//! perturbation spec, frames, layout, seed), `suite run` makes those of its shard that are not
//! complete into `datasets/<name>/` and resumes partial ones (`suite bench --ephemeral` makes,
//! runs and deletes each instead, keeping what evaluation reads; `suite regen` remakes one),
//! `suite status` tells what is there
//! and what the rest will cost, and the scheduler writers spread the shards over Slurm array
//! tasks or a Kubernetes Indexed Job.
//!
//! A suite folder:
//! ```text
//! suite.toml            the sequences (preset or hand-written)
//! datasets/<name>/      one rslam dataset per sequence (manifest, checksums; ground truth only
//!                       once `suite bench --ephemeral` deleted its frames)
//! logs/timings.jsonl    how long each run took, for time estimates
//! runs/<method>/<name>/  what `suite bench` ran: estimates, failures, logs, records
//! search/               `suite search`: its own suite folder (datasets/, runs/) and the
//!                       robustness profile (profile.json, profile.csv, report.html)
//! slurm/, k8s/          scheduler scripts and their logs
//! ```

pub mod bench;
mod disk;
mod ephemeral_plan;
mod error;
mod init;
mod layout;
mod plan;
mod preset;
mod regen;
mod run;
pub mod schedulers;
pub mod search;
mod sequence;
mod shard;
mod state;
mod status;
mod suite;
mod suite_file;
mod timings;
mod work_queue;

pub use disk::{available_bytes, folder_bytes, format_bytes};
pub use ephemeral_plan::{plan_ephemeral, EphemeralPlan};
pub use error::SuiteError;
pub use init::write_suite;
pub use plan::{plan, SequencePlan, SuitePlan};
pub use preset::{category, init_suite, Category, InitOptions, Preset, Setting, BENCHMARK_RGB};
pub use regen::{regen, Maker, Regenerated};
pub use rslam_core::dataset::Layout;
pub use run::{run_suite, RunOptions, RunSummary, SequenceOutcome, SuiteProgress};
pub use sequence::{sequence_seed, FrameCounts, Sequence, DATASETS_DIR};
pub use shard::{Shard, ShardSource};
pub use state::{inspect, SequenceState};
pub use status::{SequenceStatus, SuiteStatus};
pub use suite::Suite;
pub use suite_file::{SequenceFields, SuiteFile, SUITE_FILE};
pub use timings::{Timing, Timings};
