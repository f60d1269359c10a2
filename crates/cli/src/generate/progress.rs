//! A progress bar with frames/s, and Ctrl-C turned into an orderly stop (no manifest written).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use indicatif::{ProgressBar, ProgressStyle};

pub struct Progress {
    bar: ProgressBar,
    interrupted: Arc<AtomicBool>,
}

impl Progress {
    pub fn new(total: usize, what: &str) -> Self {
        let bar = ProgressBar::new(total as u64);
        bar.set_style(
            ProgressStyle::with_template(&format!(
                "{what} [{{bar:40}}] {{pos}}/{{len}} frames, {{per_sec}}, eta {{eta}}"
            ))
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        let interrupted = Arc::new(AtomicBool::new(false));
        let flag = interrupted.clone();
        // Only the first handler per process can be installed; later jobs keep the first flag's effect.
        let _ = ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst));
        Self { bar, interrupted }
    }

    pub fn advance(&self) -> anyhow::Result<()> {
        if self.interrupted.load(Ordering::SeqCst) {
            self.bar.abandon_with_message("interrupted");
            anyhow::bail!("interrupted: the dataset is incomplete (no rslam.json written)");
        }
        self.bar.inc(1);
        Ok(())
    }

    pub fn finish(&self) {
        self.bar.finish();
    }

    /// Frames per second over the whole run.
    pub fn rate(&self) -> f64 {
        self.bar.per_sec()
    }
}
