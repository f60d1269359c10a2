//! The terminal's view of a suite run: one bar over every frame the run draws (sequences done,
//! frames/s, ETA), one bar per sequence being made, a line per finished sequence, and Ctrl-C.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use indicatif::{MultiProgress, ProgressBar as Bar, ProgressStyle};
use rslam_pipeline::{FolderState, PipelineError, Progress};
use rslam_suite::bench::{BenchProgress, RunId, RunRecord};
use rslam_suite::{SequenceOutcome, SuiteProgress};

use crate::interrupt::interrupt_flag;

pub struct SuiteBars {
    bars: MultiProgress,
    overall: Bar,
    sequences: AtomicUsize,
    done: AtomicUsize,
    interrupted: Arc<AtomicBool>,
}

struct SequenceBar<'a> {
    suite: &'a SuiteBars,
    name: String,
    bar: Mutex<Option<Bar>>,
}

fn style(template: &str) -> ProgressStyle {
    ProgressStyle::with_template(template).unwrap_or_else(|_| ProgressStyle::default_bar())
}

impl SuiteBars {
    pub fn new() -> Self {
        let bars = MultiProgress::new();
        let overall = bars.add(Bar::new(0));
        overall.set_style(style(
            "suite [{bar:40}] {pos}/{len} frames, {per_sec}, eta {eta} · {msg}",
        ));
        Self {
            bars,
            overall,
            sequences: AtomicUsize::new(0),
            done: AtomicUsize::new(0),
            interrupted: interrupt_flag(),
        }
    }

    /// A line above the bars (or on stderr when they are hidden, e.g. in a batch job's log).
    pub fn line(&self, text: &str) {
        if self.bars.is_hidden() {
            eprintln!("{text}");
        } else {
            let _ = self.bars.println(text);
        }
    }

    pub fn finish(&self) {
        self.overall.finish();
    }

    fn sequences_message(&self) -> String {
        format!(
            "{}/{} sequences",
            self.done.load(Ordering::SeqCst),
            self.sequences.load(Ordering::SeqCst)
        )
    }
}

impl SuiteProgress for SuiteBars {
    fn begin(&self, sequences: usize, frames: usize) {
        self.sequences.store(sequences, Ordering::SeqCst);
        self.overall.set_length(frames as u64);
        self.overall.set_message(self.sequences_message());
    }

    fn sequence(&self, name: &str) -> Box<dyn Progress + '_> {
        Box::new(SequenceBar {
            suite: self,
            name: name.to_string(),
            bar: Mutex::new(None),
        })
    }

    fn sequence_done(&self, name: &str, outcome: &SequenceOutcome) {
        self.done.fetch_add(1, Ordering::SeqCst);
        self.overall.set_message(self.sequences_message());
        let line = match outcome {
            SequenceOutcome::Made {
                found: FolderState::Complete,
                ..
            } => {
                format!("{name}: completed meanwhile by another process")
            }
            SequenceOutcome::Made {
                frames,
                found,
                seconds,
            } => {
                let how = if *found == FolderState::Resume {
                    "resumed"
                } else {
                    "made"
                };
                let rate = if *seconds > 0.0 {
                    *frames as f64 / seconds
                } else {
                    0.0
                };
                format!(
                    "{name}: {how}, {frames} frames drawn in {seconds:.1} s ({rate:.1} frames/s)"
                )
            }
            SequenceOutcome::Busy => format!("{name}: being made by another process; left to it"),
            SequenceOutcome::Failed(why) => format!("{name}: FAILED: {why}"),
        };
        self.line(&line);
    }
}

impl Progress for SequenceBar<'_> {
    fn start(&self, total: usize, what: &str) {
        let bar = self.suite.bars.add(Bar::new(total as u64));
        bar.set_style(style(&format!(
            "  {} {what} [{{bar:30}}] {{pos}}/{{len}} frames, {{per_sec}}",
            self.name
        )));
        *self.bar.lock().unwrap_or_else(|p| p.into_inner()) = Some(bar);
    }

    fn advance(&self) -> Result<(), PipelineError> {
        if self.suite.interrupted.load(Ordering::SeqCst) {
            return Err(PipelineError::Interrupted);
        }
        if let Some(bar) = self.bar.lock().unwrap_or_else(|p| p.into_inner()).as_ref() {
            bar.inc(1);
        }
        self.suite.overall.inc(1);
        Ok(())
    }

    fn finish(&self) {
        if let Some(bar) = self.bar.lock().unwrap_or_else(|p| p.into_inner()).take() {
            bar.finish_and_clear();
            self.suite.bars.remove(&bar);
        }
    }
}

/// One line per finished run.
pub fn run_line(run: &RunId, record: &RunRecord) -> String {
    let outcome = match &record.failure {
        None => format!("ok in {:.1} s", record.seconds),
        Some(reason) => format!("F: {reason}"),
    };
    format!("{} {} #{}: {outcome}", run.method, run.sequence, run.repeat)
}

/// An ephemeral bench's runs: a line each above the bars.
impl BenchProgress for SuiteBars {
    fn begin(&self, runs: usize) {
        self.line(&format!("{runs} run(s) to go"));
    }

    fn run_done(&self, run: &RunId, record: &RunRecord) {
        self.line(&run_line(run, record));
    }

    fn interrupted(&self) -> &AtomicBool {
        &self.interrupted
    }
}
