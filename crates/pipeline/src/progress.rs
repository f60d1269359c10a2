//! How a run reports progress and learns that it should stop: the caller's business (a
//! progress bar and Ctrl-C in the CLI, a status line in the viewer, nothing in a library call).

use crate::PipelineError;

pub trait Progress: Sync {
    /// A stage of `total` frames begins (`what`: "rendering", "perturbing", …).
    fn start(&self, total: usize, what: &str);
    /// One more frame is done. An error (e.g. [`PipelineError::Interrupted`]) stops the run
    /// before anything marks the output complete.
    fn advance(&self) -> Result<(), PipelineError>;
    fn finish(&self);
}

/// No reports, never stops.
pub struct Silent;

impl Progress for Silent {
    fn start(&self, _total: usize, _what: &str) {}

    fn advance(&self) -> Result<(), PipelineError> {
        Ok(())
    }

    fn finish(&self) {}
}
