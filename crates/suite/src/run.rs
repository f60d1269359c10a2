//! `rslam suite run`: makes every sequence of a shard that is not complete, `jobs` at a time on
//! one GPU, resuming partial ones, leaving complete ones alone. A sequence is locked while a
//! process makes it, so that two runs over the same shard never write into one folder.

use std::fs::{File, TryLockError};
use std::path::{Path, PathBuf};
use std::time::Instant;

use rslam_core::dataset::refuse_symlinks;
use rslam_gpu::GpuContext;
use rslam_pipeline::{FolderState, PipelineError, Progress, SceneCache};

use crate::disk::{available_bytes, format_bytes};
use crate::plan::plan;
use crate::sequence::{Sequence, DATASETS_DIR};
use crate::shard::Shard;
use crate::state::{inspect, SequenceState};
use crate::timings::{Timing, Timings};
use crate::work_queue::run_queue;
use crate::{Suite, SuiteError};

const LOCKS_DIR: &str = ".locks";

#[derive(Clone, Copy, Debug)]
pub struct RunOptions {
    pub shard: Shard,
    /// Sequences made at once.
    pub jobs: usize,
    /// Remake conflicting sequences (another definition, damaged) instead of leaving them.
    pub force: bool,
    /// Refuse to start when the file system cannot hold what is left to write.
    pub check_space: bool,
}

/// How a suite run reports, per sequence and over the whole run.
pub trait SuiteProgress: Sync {
    /// The run will make `sequences` sequences, drawing `frames` frames in all.
    fn begin(&self, sequences: usize, frames: usize);
    /// The per-frame progress of one sequence being made.
    fn sequence(&self, name: &str) -> Box<dyn Progress + '_>;
    /// One sequence ended; `outcome` says how.
    fn sequence_done(&self, name: &str, outcome: &SequenceOutcome);
}

#[derive(Clone, Debug, PartialEq)]
pub enum SequenceOutcome {
    Made {
        frames: usize,
        found: FolderState,
        seconds: f64,
    },
    /// Another process holds its lock.
    Busy,
    Failed(String),
}

/// What one `suite run` did.
#[derive(Clone, Debug, Default)]
pub struct RunSummary {
    pub in_shard: usize,
    pub already_complete: usize,
    /// Left alone: their frames were deleted after their runs (`suite regen` remakes one).
    pub frames_deleted: Vec<String>,
    pub made: Vec<String>,
    pub busy: Vec<String>,
    /// Left alone: (name, why).
    pub conflicts: Vec<(String, String)>,
    pub failed: Vec<(String, String)>,
}

pub fn run_suite(
    ctx: &GpuContext,
    suite: &Suite,
    options: RunOptions,
    progress: &dyn SuiteProgress,
) -> Result<RunSummary, SuiteError> {
    let mut summary = RunSummary::default();
    let mut to_make = Vec::new();
    for (sequence, state) in suite.shard_states(options.shard) {
        summary.in_shard += 1;
        match state {
            SequenceState::Complete => summary.already_complete += 1,
            SequenceState::FramesDeleted => summary.frames_deleted.push(sequence.name.clone()),
            SequenceState::Conflict(reason) if !options.force => {
                summary.conflicts.push((sequence.name.clone(), reason))
            }
            state => to_make.push((sequence, state)),
        }
    }
    let planned = plan(&suite.dir, &to_make)?;
    if options.check_space {
        check_space(&suite.dir, planned.bytes_to_write, to_make.len())?;
    }
    progress.begin(to_make.len(), planned.frames_to_render);
    let outcomes = make_all(ctx, suite, &to_make, options, progress)?;
    for (sequence, outcome) in to_make.iter().map(|(s, _)| s).zip(outcomes) {
        match outcome {
            Some(SequenceOutcome::Made { .. }) => summary.made.push(sequence.name.clone()),
            Some(SequenceOutcome::Busy) => summary.busy.push(sequence.name.clone()),
            Some(SequenceOutcome::Failed(why)) => summary.failed.push((sequence.name.clone(), why)),
            None => {}
        }
    }
    Ok(summary)
}

/// Makes the sequences on `jobs` threads; `None` for those not started because the run was
/// interrupted, which is returned as the error once every started sequence has stopped.
fn make_all(
    ctx: &GpuContext,
    suite: &Suite,
    to_make: &[(&Sequence, SequenceState)],
    options: RunOptions,
    progress: &dyn SuiteProgress,
) -> Result<Vec<Option<SequenceOutcome>>, SuiteError> {
    let (outcomes, interrupted) = run_queue(to_make, options.jobs, |(sequence, state)| {
        let outcome = match make_one(ctx, suite, sequence, state, progress) {
            Err(SuiteError::Pipeline(PipelineError::Interrupted)) => {
                return Err(PipelineError::Interrupted)
            }
            Err(e) => SequenceOutcome::Failed(e.to_string()),
            Ok(outcome) => outcome,
        };
        progress.sequence_done(&sequence.name, &outcome);
        Ok(outcome)
    });
    match interrupted {
        Some(e) => Err(e.into()),
        None => Ok(outcomes),
    }
}

fn make_one(
    ctx: &GpuContext,
    suite: &Suite,
    sequence: &Sequence,
    state: &SequenceState,
    progress: &dyn SuiteProgress,
) -> Result<SequenceOutcome, SuiteError> {
    refuse_symlinks(&suite.dir, &sequence.dir(&suite.dir))?;
    let Some(_lock) = lock(&suite.dir, &sequence.name)? else {
        return Ok(SequenceOutcome::Busy);
    };
    // Another process may have finished it between the inspection and the lock.
    let scenes = SceneCache::default();
    if inspect(sequence, &suite.dir, &scenes) == SequenceState::Complete {
        return Ok(SequenceOutcome::Made {
            frames: 0,
            found: FolderState::Complete,
            seconds: 0.0,
        });
    }
    let replace = match state {
        SequenceState::Conflict(_) => Replace::Anything,
        // An unfinished run of another job (another GPU, an edited row) was never usable.
        SequenceState::Partial => Replace::OtherJob,
        _ => Replace::Nothing,
    };
    let out = sequence.dir(&suite.dir);
    make_sequence(ctx, suite, sequence, &out, replace, &scenes, progress)
}

/// What of an output folder's earlier content a sequence being made replaces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Replace {
    /// Nothing: another job's output is an error.
    Nothing,
    /// Another job's output; this job's is resumed or kept.
    OtherJob,
    /// Whatever is there: it starts over.
    Anything,
}

/// Makes `sequence` into `out`, replacing what `replace` says, and records how long it took.
pub(crate) fn make_sequence(
    ctx: &GpuContext,
    suite: &Suite,
    sequence: &Sequence,
    out: &Path,
    replace: Replace,
    scenes: &SceneCache,
    progress: &dyn SuiteProgress,
) -> Result<SequenceOutcome, SuiteError> {
    let started = Instant::now();
    let sequence_progress = progress.sequence(&sequence.name);
    let render =
        |force| sequence.render_into(ctx, &suite.dir, out, force, scenes, &*sequence_progress);
    let (made, found) = match render(replace == Replace::Anything) {
        Err(PipelineError::OtherJob { .. }) if replace == Replace::OtherJob => render(true)?,
        report => report?,
    };
    let seconds = started.elapsed().as_secs_f64();
    if made > 0 {
        Timings::append(
            &suite.dir,
            &Timing {
                sequence: sequence.name.clone(),
                frames: made,
                seconds,
                adapter: ctx.describe(),
            },
        )?;
    }
    Ok(SequenceOutcome::Made {
        frames: made,
        found,
        seconds,
    })
}

/// An exclusive lock on the sequence, held until the returned file is dropped; `None` when
/// another process holds it.
pub(crate) fn lock(suite_dir: &Path, name: &str) -> Result<Option<File>, SuiteError> {
    let dir: PathBuf = suite_dir.join(DATASETS_DIR).join(LOCKS_DIR);
    std::fs::create_dir_all(&dir).map_err(|e| SuiteError::io(&dir, e))?;
    let path = dir.join(format!("{name}.lock"));
    let file = File::create(&path).map_err(|e| SuiteError::io(&path, e))?;
    match file.try_lock() {
        Ok(()) => Ok(Some(file)),
        Err(TryLockError::WouldBlock) => Ok(None),
        Err(TryLockError::Error(e)) => Err(SuiteError::io(&path, e)),
    }
}

fn check_space(suite_dir: &Path, needed: u64, sequences: usize) -> Result<(), SuiteError> {
    let target = suite_dir.join(DATASETS_DIR);
    let available = available_bytes(&target)?;
    if needed > available {
        return Err(SuiteError::NoSpace {
            path: target,
            needed: format_bytes(needed),
            available: format_bytes(available),
            sequences,
        });
    }
    Ok(())
}
