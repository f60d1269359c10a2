//! `rslam suite bench --ephemeral`: the whole matrix on an ordinary disk. Each sequence of the
//! shard is made, run by every method and repeat still to run, and its frames deleted, keeping
//! its manifest, checksum list and ground truth (what `suite report`, `eval --runs` and `suite
//! regen` read) under `datasets/<name>/`. `jobs` sequences are in flight, each running its
//! methods one after another: at most `jobs` frame sets on disk and `jobs` methods at once.
//!
//! Frames are made in place, or in node-local scratch (`scratch`) and only the kept files copied
//! to the suite folder. A sequence whose runs are all finished and whose ground truth is kept is
//! never made again; one interrupted is made again (resumed, when its scratch is still there),
//! its finished runs kept.

use std::path::{Path, PathBuf};

use rslam_core::dataset::{
    blake3_hex, copy_without_frames, delete_frames, read_frames_deleted, refuse_symlinks,
    DatasetFormat, FramesDeleted, Layout,
};
use rslam_core::remove_if_present;
use rslam_gpu::GpuContext;
use rslam_pipeline::{PipelineError, SceneCache};

use super::method::Method;
use super::run_method::{
    check_layouts, run_reported, runs_left, BenchOptions, BenchProgress, RunId,
};
use crate::run::{lock, make_sequence, Replace, SequenceOutcome, SuiteProgress};
use crate::sequence::{Sequence, DATASETS_DIR};
use crate::state::{inspect, SequenceState};
use crate::work_queue::run_queue;
use crate::{Suite, SuiteError};

/// Where the kept files of a sequence made in scratch are gathered before they replace its
/// folder under `datasets/`.
const KEPT_PARTIAL_DIR: &str = ".kept-partial";

#[derive(Clone, Debug)]
pub struct EphemeralOptions {
    /// `jobs`: sequences in flight (and so methods running at once).
    pub bench: BenchOptions,
    /// A node-local folder to make the frames in; `None`: in place under `datasets/`.
    pub scratch: Option<PathBuf>,
}

/// What happened to one sequence.
#[derive(Clone, Debug, PartialEq)]
pub enum EphemeralOutcome {
    /// Made (or found complete), run, and its frames deleted: how many and how large.
    Used(FramesDeleted),
    /// Another process holds its lock.
    Busy,
    /// It could not be made: its runs did not run.
    Failed(String),
}

#[derive(Clone, Debug, Default)]
pub struct EphemeralSummary {
    /// Runs finished before this bench.
    pub runs_done_before: usize,
    pub runs_succeeded: usize,
    pub runs_failed: Vec<(RunId, String)>,
    /// Sequences whose runs were all finished and frames deleted already.
    pub sequences_done_before: usize,
    pub used: Vec<(String, FramesDeleted)>,
    pub busy: Vec<String>,
    /// Left alone: (name, why), as `suite run` leaves them.
    pub conflicts: Vec<(String, String)>,
    pub failed: Vec<(String, String)>,
}

/// Benches the shard ephemerally; `sequences` reports the making of each, `runs` each run and
/// carries Ctrl-C.
pub fn bench_ephemeral(
    ctx: &GpuContext,
    suite: &Suite,
    methods: &[Method],
    options: &EphemeralOptions,
    sequences: &dyn SuiteProgress,
    runs: &dyn BenchProgress,
) -> Result<EphemeralSummary, SuiteError> {
    let mut summary = EphemeralSummary::default();
    let mut work = Vec::new();
    for (sequence, state) in suite.shard_states(options.bench.shard) {
        if let SequenceState::Conflict(reason) = state {
            summary.conflicts.push((sequence.name.clone(), reason));
            continue;
        }
        refuse_bags(sequence)?;
        let left = runs_left(suite, methods, sequence, options.bench.retry_failed).len();
        let all: usize = methods.iter().map(|m| m.repeats).sum();
        summary.runs_done_before += all - left;
        if left == 0 && state == SequenceState::FramesDeleted {
            summary.sequences_done_before += 1;
            continue;
        }
        let to_draw = match state {
            SequenceState::Complete => 0,
            _ => sequence.frame_counts(&suite.dir)?.rendered,
        };
        work.push((sequence, left, to_draw));
    }
    let sequences_to_use: Vec<&Sequence> = work.iter().map(|(s, ..)| *s).collect();
    check_layouts(methods, &sequences_to_use)?;
    runs.begin(work.iter().map(|(_, left, _)| left).sum());
    let to_make = work.iter().filter(|(.., to_draw)| *to_draw > 0).count();
    sequences.begin(to_make, work.iter().map(|(.., to_draw)| to_draw).sum());
    let scratch = match &options.scratch {
        Some(dir) => Some(suite_scratch(suite, dir)?),
        None => None,
    };
    let bench = Bench {
        ctx,
        suite,
        methods,
        retry_failed: options.bench.retry_failed,
        scratch: scratch.as_deref(),
    };
    let (outcomes, interrupted) = run_queue(&work, options.bench.jobs, |(sequence, ..)| {
        let used = bench.use_sequence(sequence, sequences, runs);
        let outcome = match used {
            Ok(outcome) => outcome,
            Err(
                SuiteError::Pipeline(PipelineError::Interrupted) | SuiteError::BenchInterrupted,
            ) => return Err(SuiteError::BenchInterrupted),
            Err(e) => (EphemeralOutcome::Failed(e.to_string()), Vec::new()),
        };
        if let EphemeralOutcome::Failed(why) = &outcome.0 {
            sequences.sequence_done(&sequence.name, &SequenceOutcome::Failed(why.clone()));
        }
        Ok(outcome)
    });
    if let Some(error) = interrupted {
        return Err(error);
    }
    for ((sequence, ..), outcome) in work.iter().zip(outcomes) {
        let Some((outcome, records)) = outcome else {
            continue;
        };
        for (id, failure) in records {
            match failure {
                None => summary.runs_succeeded += 1,
                Some(reason) => summary.runs_failed.push((id, reason)),
            }
        }
        match outcome {
            EphemeralOutcome::Used(deleted) => summary.used.push((sequence.name.clone(), deleted)),
            EphemeralOutcome::Busy => summary.busy.push(sequence.name.clone()),
            EphemeralOutcome::Failed(why) => summary.failed.push((sequence.name.clone(), why)),
        }
    }
    if let Some(scratch) = &scratch {
        // Empty once every sequence of every shard run here is done; another shard may be using it.
        let _ = std::fs::remove_dir(scratch);
    }
    Ok(summary)
}

/// A bag holds its ground truth among its frames: deleting them would leave nothing to
/// evaluate against.
fn refuse_bags(sequence: &Sequence) -> Result<(), SuiteError> {
    if sequence.layout() == Layout::Camera(DatasetFormat::Ros2) {
        return Err(SuiteError::option(
            "--ephemeral",
            format!(
                "sequence '{}' is a ROS 2 bag, whose ground truth is one of its topics: bench bags with their datasets kept",
                sequence.name
            ),
        ));
    }
    Ok(())
}

/// This suite's own folder in `scratch`, so that suites sharing a node's scratch never meet.
fn suite_scratch(suite: &Suite, scratch: &Path) -> Result<PathBuf, SuiteError> {
    let canonical = suite
        .dir
        .canonicalize()
        .map_err(|e| SuiteError::io(&suite.dir, e))?;
    let digest = blake3_hex(canonical.as_os_str().as_encoded_bytes());
    Ok(scratch.join(format!("rslam-suite-{}", &digest[..16])))
}

type RunOutcomes = Vec<(RunId, Option<String>)>;

/// What every sequence of one ephemeral bench shares.
struct Bench<'a> {
    ctx: &'a GpuContext,
    suite: &'a Suite,
    methods: &'a [Method],
    retry_failed: bool,
    /// This suite's folder in the scratch, if any.
    scratch: Option<&'a Path>,
}

impl Bench<'_> {
    /// Makes one sequence (unless complete in place), runs what is left on it, keeps what
    /// evaluation reads and deletes its frames; all under the sequence's lock.
    fn use_sequence(
        &self,
        sequence: &Sequence,
        sequences: &dyn SuiteProgress,
        runs: &dyn BenchProgress,
    ) -> Result<(EphemeralOutcome, RunOutcomes), SuiteError> {
        let suite = self.suite;
        let kept = sequence.dir(&suite.dir);
        refuse_symlinks(&suite.dir, &kept)?;
        let Some(_lock) = lock(&suite.dir, &sequence.name)? else {
            return Ok((EphemeralOutcome::Busy, Vec::new()));
        };
        // Another process may have used it between the inspection and the lock.
        let scenes = SceneCache::default();
        let state = inspect(sequence, &suite.dir, &scenes);
        let left = runs_left(suite, self.methods, sequence, self.retry_failed);
        if left.is_empty() && state == SequenceState::FramesDeleted {
            if let Some(deleted) = read_frames_deleted(&kept)? {
                return Ok((EphemeralOutcome::Used(deleted), Vec::new()));
            }
        }
        let frames = match (self.scratch, &state) {
            (_, SequenceState::Complete) | (None, _) => kept.clone(),
            (Some(scratch), _) => scratch.join(&sequence.name),
        };
        if state != SequenceState::Complete {
            // In scratch, another job's output is a leftover of an edited row.
            let replace = match state == SequenceState::Partial || frames != kept {
                true => Replace::OtherJob,
                false => Replace::Nothing,
            };
            std::fs::create_dir_all(&frames).map_err(|e| SuiteError::io(&frames, e))?;
            let made = make_sequence(
                self.ctx, suite, sequence, &frames, replace, &scenes, sequences,
            )?;
            sequences.sequence_done(&sequence.name, &made);
        }
        let mut outcomes = Vec::with_capacity(left.len());
        for (method, repeat) in &left {
            let (id, record) = run_reported(suite, method, sequence, *repeat, &frames, runs)?;
            outcomes.push((id, record.failure));
        }
        let deleted = match frames == kept {
            true => delete_frames(&kept)?,
            false => keep_from_scratch(suite, sequence, &frames)?,
        };
        Ok((EphemeralOutcome::Used(deleted), outcomes))
    }
}

/// Copies what is kept of the sequence made in `frames` over its folder under `datasets/`, then
/// removes `frames`.
fn keep_from_scratch(
    suite: &Suite,
    sequence: &Sequence,
    frames: &Path,
) -> Result<FramesDeleted, SuiteError> {
    let gathering = suite
        .dir
        .join(DATASETS_DIR)
        .join(KEPT_PARTIAL_DIR)
        .join(&sequence.name);
    remove_if_present(&gathering)?;
    let deleted = copy_without_frames(frames, &gathering)?;
    let kept = sequence.dir(&suite.dir);
    remove_if_present(&kept)?;
    std::fs::rename(&gathering, &kept).map_err(|e| SuiteError::io(&gathering, e))?;
    if let Some(parent) = gathering.parent() {
        // Fails, harmlessly, while another sequence is being gathered.
        let _ = std::fs::remove_dir(parent);
    }
    remove_if_present(frames)?;
    Ok(deleted)
}
