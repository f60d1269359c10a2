//! Runs methods over a suite: which runs are left, each in its own scratch folder, and what
//! counts as a failure (a crash, a timeout, no estimate, an estimate that does not read).

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use rslam_core::dataset::refuse_symlinks;
use rslam_core::trajectory_io::{read_trajectory, TrajectoryFormat};

use super::method::{Method, RunPlaces};
use super::process::{run_process, Ending};
use super::record::{RunFiles, RunRecord};
use crate::sequence::Sequence;
use crate::shard::Shard;
use crate::state::SequenceState;
use crate::work_queue::run_queue;
use crate::{Suite, SuiteError};

#[derive(Clone, Copy, Debug)]
pub struct BenchOptions {
    pub shard: Shard,
    /// Runs at once.
    pub jobs: usize,
    /// Run again the runs that failed before (finished successes are always kept).
    pub retry_failed: bool,
}

/// One run: a method on a sequence, one repeat.
#[derive(Clone, Debug, PartialEq)]
pub struct RunId {
    pub method: String,
    pub sequence: String,
    pub repeat: usize,
}

pub trait BenchProgress: Sync {
    fn begin(&self, runs: usize);
    fn run_done(&self, run: &RunId, record: &RunRecord);
    /// Set on Ctrl-C: running methods are killed and the bench stops without recording them.
    fn interrupted(&self) -> &AtomicBool;
}

#[derive(Clone, Debug, Default)]
pub struct BenchSummary {
    pub already_done: usize,
    pub succeeded: usize,
    pub failed: Vec<(RunId, String)>,
    /// Sequences of the shard not complete yet (make them with `rslam suite run`).
    pub sequences_not_made: Vec<String>,
    /// Sequences whose frames were deleted after their runs (`--ephemeral` runs them again).
    pub sequences_frames_deleted: Vec<String>,
}

pub fn bench_suite(
    suite: &Suite,
    methods: &[Method],
    options: BenchOptions,
    progress: &dyn BenchProgress,
) -> Result<BenchSummary, SuiteError> {
    let mut summary = BenchSummary::default();
    let mut sequences = Vec::new();
    for (sequence, state) in suite.shard_states(options.shard) {
        match state {
            SequenceState::Complete => sequences.push(sequence),
            SequenceState::FramesDeleted => {
                summary.sequences_frames_deleted.push(sequence.name.clone())
            }
            _ => summary.sequences_not_made.push(sequence.name.clone()),
        }
    }
    check_layouts(methods, &sequences)?;
    let mut to_run = Vec::new();
    for method in methods {
        for sequence in &sequences {
            let left = runs_left(
                suite,
                std::slice::from_ref(method),
                sequence,
                options.retry_failed,
            );
            summary.already_done += method.repeats - left.len();
            to_run.extend(
                left.into_iter()
                    .map(|(method, repeat)| (method, *sequence, repeat)),
            );
        }
    }
    progress.begin(to_run.len());
    let (records, interrupted) = run_queue(&to_run, options.jobs, |&(method, sequence, repeat)| {
        let dataset = sequence.dir(&suite.dir);
        run_reported(suite, method, sequence, repeat, &dataset, progress)
    });
    if let Some(error) = interrupted {
        return Err(error);
    }
    for (id, record) in records.into_iter().flatten() {
        match record.failure {
            None => summary.succeeded += 1,
            Some(reason) => summary.failed.push((id, reason)),
        }
    }
    Ok(summary)
}

/// The (method, repeat) runs of `methods` on `sequence` without a record (or, `retry_failed`,
/// with a failed one), in method order.
pub(crate) fn runs_left<'m>(
    suite: &Suite,
    methods: &'m [Method],
    sequence: &Sequence,
    retry_failed: bool,
) -> Vec<(&'m Method, usize)> {
    let mut left = Vec::new();
    for method in methods {
        for repeat in 0..method.repeats {
            let files = RunFiles::new(&suite.dir, &method.name, &sequence.name, repeat);
            match files.read_record() {
                Some(r) if r.failure.is_none() || !retry_failed => {}
                _ => left.push((method, repeat)),
            }
        }
    }
    left
}

/// A method reads one layout; every sequence it runs on must be in it.
pub(crate) fn check_layouts(methods: &[Method], sequences: &[&Sequence]) -> Result<(), SuiteError> {
    for method in methods {
        let other: Vec<&&Sequence> = sequences
            .iter()
            .filter(|s| s.layout() != method.reads)
            .collect();
        if let Some(first) = other.first() {
            return Err(SuiteError::option(
                "--methods",
                format!(
                    "method '{}' reads the {} layout but {} sequence(s) of the suite are {} (e.g. {}): make the suite with {}",
                    method.name, method.reads, other.len(), first.layout(), first.name, crate::layout::how_to_make(method.reads)
                ),
            ));
        }
    }
    Ok(())
}

/// [`run_once`], reported to `progress` once recorded.
pub(crate) fn run_reported(
    suite: &Suite,
    method: &Method,
    sequence: &Sequence,
    repeat: usize,
    dataset: &Path,
    progress: &dyn BenchProgress,
) -> Result<(RunId, RunRecord), SuiteError> {
    let record = run_once(
        suite,
        method,
        sequence,
        repeat,
        dataset,
        progress.interrupted(),
    )?;
    let id = RunId {
        method: method.name.clone(),
        sequence: sequence.name.clone(),
        repeat,
    };
    progress.run_done(&id, &record);
    Ok((id, record))
}

/// One run on the sequence's frames in `dataset`, recorded; interrupted, it records nothing and
/// runs again next time.
fn run_once(
    suite: &Suite,
    method: &Method,
    sequence: &Sequence,
    repeat: usize,
    dataset: &Path,
    interrupted: &AtomicBool,
) -> Result<RunRecord, SuiteError> {
    let files = RunFiles::new(&suite.dir, &method.name, &sequence.name, repeat);
    refuse_symlinks(&suite.dir, &files.dir)?;
    files.clear()?;
    let work = files.work();
    std::fs::create_dir_all(&work).map_err(|e| SuiteError::io(&work, e))?;
    let dataset = dataset
        .canonicalize()
        .map_err(|e| SuiteError::io(dataset, e))?;
    let work = work.canonicalize().map_err(|e| SuiteError::io(&work, e))?;
    let estimate = work.join("estimate.txt");
    let log = files.log();
    let log = std::path::absolute(&log).unwrap_or(log);
    let camera = dataset.join(sequence.layout().camera_file());
    let places = RunPlaces {
        dataset: &dataset,
        estimate: &estimate,
        camera: &camera,
        sequence: &sequence.name,
        repeat,
        log: &log,
        work: &work,
    };
    let command = method.command_for(&places);
    let report = run_process(
        &command,
        &work,
        &log,
        Duration::from_secs_f64(method.timeout_s),
        interrupted,
    );
    let report = match report {
        Ok(report) => report,
        Err(e) => {
            let record = failed_record(method, sequence, repeat, command, e.to_string());
            return finish(&files, record);
        }
    };
    let failure = match report.ending {
        Ending::Interrupted => {
            files.clear()?;
            return Err(SuiteError::BenchInterrupted);
        }
        Ending::Exited(0) => check_estimate(&estimate).err(),
        Ending::Exited(code) => Some(format!("exit status {code} (see {})", log.display())),
        Ending::Signalled(signal) => {
            Some(format!("killed by signal {signal} (see {})", log.display()))
        }
        Ending::TimedOut => Some(format!("timed out after {} s", method.timeout_s)),
    };
    let succeeded = failure.is_none();
    let kept_mesh = keep(
        method
            .mesh_for(&places)
            .filter(|m| m.is_file() && succeeded),
        files.mesh(),
    )?;
    let kept_renders = keep(
        method
            .renders_for(&places)
            .filter(|r| r.is_dir() && succeeded),
        files.renders(),
    )?;
    if failure.is_none() {
        std::fs::rename(&estimate, files.estimate()).map_err(|e| SuiteError::io(&estimate, e))?;
    }
    let record = RunRecord {
        method: method.name.clone(),
        sequence: sequence.name.clone(),
        repeat,
        command,
        failure,
        exit_code: match report.ending {
            Ending::Exited(code) => Some(code),
            _ => None,
        },
        seconds: report.seconds,
        peak_rss_mb: report.peak_rss_bytes.map(|b| b as f64 / 1e6),
        mesh: kept_mesh,
        renders: kept_renders,
    };
    finish(&files, record)
}

/// Moves what the run wrote (a file or a folder) to where the runs folder keeps it.
fn keep(written: Option<PathBuf>, kept: PathBuf) -> Result<Option<PathBuf>, SuiteError> {
    let Some(written) = written else {
        return Ok(None);
    };
    std::fs::rename(&written, &kept).map_err(|e| SuiteError::io(&written, e))?;
    Ok(Some(kept))
}

fn failed_record(
    method: &Method,
    sequence: &Sequence,
    repeat: usize,
    command: Vec<String>,
    reason: String,
) -> RunRecord {
    RunRecord {
        method: method.name.clone(),
        sequence: sequence.name.clone(),
        repeat,
        command,
        failure: Some(reason),
        exit_code: None,
        seconds: 0.0,
        peak_rss_mb: None,
        mesh: None,
        renders: None,
    }
}

/// Writes the failure file (if any), removes the scratch folder, then the record.
fn finish(files: &RunFiles, record: RunRecord) -> Result<RunRecord, SuiteError> {
    if let Some(reason) = &record.failure {
        let path = files.failed();
        std::fs::write(&path, format!("{reason}\n")).map_err(|e| SuiteError::io(&path, e))?;
    }
    let work = files.work();
    std::fs::remove_dir_all(&work).map_err(|e| SuiteError::io(&work, e))?;
    files.write_record(&record)?;
    Ok(record)
}

fn check_estimate(estimate: &Path) -> Result<(), String> {
    if !estimate.is_file() {
        return Err("exited 0 but wrote no estimate".into());
    }
    read_trajectory(estimate, Some(TrajectoryFormat::Tum))
        .map(|_| ())
        .map_err(|e| format!("estimate unreadable: {e}"))
}
