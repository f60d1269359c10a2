//! The terminal's view of a run: a progress bar with frames/s that stops the run on Ctrl-C.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use indicatif::{ProgressBar as Bar, ProgressStyle};
use rslam_pipeline::{PipelineError, Progress};

use crate::interrupt::interrupt_flag;

pub struct ProgressBar {
    bar: Mutex<Option<Bar>>,
    interrupted: Arc<AtomicBool>,
}

impl ProgressBar {
    pub fn new() -> Self {
        Self {
            bar: Mutex::new(None),
            interrupted: interrupt_flag(),
        }
    }

    /// Frames per second of the last stage, for stderr.
    pub fn rate(&self) -> Option<f64> {
        let bar = self.bar.lock().unwrap_or_else(|p| p.into_inner());
        let bar = bar.as_ref()?;
        let seconds = bar.elapsed().as_secs_f64();
        (seconds > 0.0 && bar.position() > 0).then(|| bar.position() as f64 / seconds)
    }
}

impl Progress for ProgressBar {
    fn start(&self, total: usize, what: &str) {
        let bar = Bar::new(total as u64);
        bar.set_style(
            ProgressStyle::with_template(&format!(
                "{what} [{{bar:40}}] {{pos}}/{{len}} frames, {{per_sec}}, eta {{eta}}"
            ))
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        *self.bar.lock().unwrap_or_else(|p| p.into_inner()) = Some(bar);
    }

    fn advance(&self) -> Result<(), PipelineError> {
        let bar = self.bar.lock().unwrap_or_else(|p| p.into_inner());
        if self.interrupted.load(Ordering::SeqCst) {
            if let Some(bar) = bar.as_ref() {
                bar.abandon_with_message("interrupted");
            }
            return Err(PipelineError::Interrupted);
        }
        if let Some(bar) = bar.as_ref() {
            bar.inc(1);
        }
        Ok(())
    }

    fn finish(&self) {
        if let Some(bar) = self.bar.lock().unwrap_or_else(|p| p.into_inner()).as_ref() {
            bar.finish();
        }
    }
}
