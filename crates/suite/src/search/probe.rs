//! One probe of the search: a method at one severity of one family on one scene. Its sequences
//! (one per seed) are made, run by the method's repeats and their frames deleted, as `suite
//! bench --ephemeral` does (or kept, as `suite run` and `suite bench` do), under `search/`; runs already recorded there are not made again, so a
//! killed search resumes where it stopped.

use std::path::{Path, PathBuf};
use std::time::Duration;

use rslam_core::trajectory_io::{read_trajectory_with, ReadOptions};
use rslam_eval::runs::ground_truth_of;
use rslam_eval::{evaluate_files, EvalOptions};
use rslam_gpu::GpuContext;
use rslam_perturb::Severity;

use super::criterion::RunOutcome;
use super::SearchProgress;
use crate::bench::{
    bench_ephemeral, bench_suite, BenchOptions, EphemeralOptions, Method, RunFiles,
};
use crate::run::{run_suite, RunOptions};
use crate::sequence::Sequence;
use crate::suite::resolve;
use crate::suite_file::SequenceFields;
use crate::{Shard, Suite, SuiteError};

/// How long to wait before trying again a sequence another process (another shard) holds.
const BUSY_WAIT: Duration = Duration::from_secs(2);

pub(super) struct Prober {
    /// The search's own suite folder, `DIR/search`.
    pub dir: PathBuf,
    /// What every probe's row shares (the `[defaults]` of `DIR/suite.toml`, if any).
    pub template: SequenceFields,
    pub seed: u64,
    pub seeds: usize,
    pub jobs: usize,
    pub scratch: Option<PathBuf>,
    /// Keep each sequence's frames (`suite run`, then `suite bench`) instead of deleting them.
    pub keep: bool,
}

impl Prober {
    /// Checks the rows a family's probes on `scene` get.
    pub fn row_check(&self, scene: &str, family: &str) -> Result<(), SuiteError> {
        self.sequences(scene, family, Severity::MAX).map(|_| ())
    }

    /// The rows of one probe's sequences: `<scene>__clean` or `<scene>__<family>-<severity>`,
    /// and for seeds after the first the same with `-seed<k>`; the rest comes from the template.
    pub fn rows(&self, scene: &str, family: &str, severity: Severity) -> Vec<SequenceFields> {
        let base = match severity.is_clean() {
            true => format!("{scene}__clean"),
            false => format!("{scene}__{family}-{severity}"),
        };
        (0..self.seeds)
            .map(|k| SequenceFields {
                name: Some(match k {
                    0 => base.clone(),
                    k => format!("{base}-seed{k}"),
                }),
                scene: Some(scene.to_string()),
                perturb: (!severity.is_clean()).then(|| format!("{family}:{severity}")),
                ..SequenceFields::default()
            })
            .collect()
    }

    /// The sequences of one probe ([`Prober::rows`] filled from the template).
    pub fn sequences(
        &self,
        scene: &str,
        family: &str,
        severity: Severity,
    ) -> Result<Vec<Sequence>, SuiteError> {
        (self.rows(scene, family, severity).iter())
            .map(|row| {
                resolve(&row.or(&self.template), self.seed, &self.dir)
                    .map_err(|m| SuiteError::option("--scenes", m))
            })
            .collect()
    }

    /// Makes, runs and evaluates `sequences` with `method`: one outcome per sequence and repeat.
    pub fn run(
        &self,
        ctx: &GpuContext,
        progress: &dyn SearchProgress,
        method: &Method,
        sequences: Vec<Sequence>,
    ) -> Result<Vec<RunOutcome>, SuiteError> {
        let suite = Suite {
            dir: self.dir.clone(),
            seed: self.seed,
            sequences,
        };
        let options = EphemeralOptions {
            bench: BenchOptions {
                shard: Shard::WHOLE,
                jobs: self.jobs,
                retry_failed: false,
            },
            scratch: self.scratch.clone(),
        };
        let methods = std::slice::from_ref(method);
        loop {
            let (failed, conflicts, busy) = match self.keep {
                false => {
                    let s = bench_ephemeral(ctx, &suite, methods, &options, progress, progress)?;
                    (s.failed, s.conflicts, s.busy)
                }
                true => {
                    let run = RunOptions {
                        shard: Shard::WHOLE,
                        jobs: self.jobs,
                        force: false,
                        check_space: true,
                    };
                    let s = run_suite(ctx, &suite, run, progress)?;
                    (s.failed, s.conflicts, s.busy)
                }
            };
            let unusable: Vec<String> = (failed.iter().chain(&conflicts))
                .map(|(name, why)| format!("{name}: {why}"))
                .collect();
            if !unusable.is_empty() {
                return Err(SuiteError::SequencesFailed {
                    count: unusable.len(),
                    summary: unusable.join("; "),
                });
            }
            if busy.is_empty() {
                break;
            }
            std::thread::sleep(BUSY_WAIT);
        }
        if self.keep {
            bench_suite(&suite, methods, options.bench, progress)?;
        }
        let mut outcomes = Vec::new();
        for sequence in &suite.sequences {
            for repeat in 0..method.repeats {
                outcomes.push(outcome(&self.dir, method, sequence, repeat)?);
            }
        }
        Ok(outcomes)
    }
}

/// What one recorded run gave: failed, or its ATE and SR against the kept ground truth (an
/// estimate that does not evaluate, e.g. no pose near a ground-truth stamp, counts as failed).
fn outcome(
    dir: &Path,
    method: &Method,
    sequence: &Sequence,
    repeat: usize,
) -> Result<RunOutcome, SuiteError> {
    let files = RunFiles::new(dir, &method.name, &sequence.name, repeat);
    match files.read_record() {
        Some(record) if record.failure.is_none() => {}
        _ => return Ok(RunOutcome::FAILED),
    }
    let dataset = sequence.dir(dir);
    let ground_truth = ground_truth_of(&dataset).ok_or_else(|| {
        SuiteError::option(
            "--methods",
            format!(
                "{}: no ground truth kept to evaluate against",
                dataset.display()
            ),
        )
    })?;
    let read = ReadOptions::default();
    let gt = read_trajectory_with(&ground_truth, &read)?;
    let evaluated = read_trajectory_with(&files.estimate(), &read)
        .map_err(rslam_eval::EvalError::from)
        .and_then(|est| evaluate_files(&est, &gt, &EvalOptions::default()));
    Ok(match evaluated {
        Ok(e) => RunOutcome {
            ate: Some(e.ate.rmse),
            sr: e.success_rate.sr,
        },
        Err(_) => RunOutcome::FAILED,
    })
}
