use std::path::PathBuf;

use rslam_core::CoreError;
use rslam_eval::EvalError;
use rslam_gpu::GpuError;
use rslam_perturb::PerturbError;
use rslam_pipeline::PipelineError;

/// Errors of the viewer; each names the file, flag or spec that was wrong. Shown in the window as
/// one line, never a panic.
#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    #[error(transparent)]
    Pipeline(#[from] PipelineError),
    #[error(transparent)]
    Core(#[from] CoreError),
    #[error(transparent)]
    Gpu(#[from] GpuError),
    #[error("spec: {0}")]
    Perturb(#[from] PerturbError),
    #[error("{}: {source}", path.display())]
    Eval {
        path: PathBuf,
        #[source]
        source: EvalError,
    },
    #[error("window: {message}")]
    Window { message: String },
    #[error("{}: {message}", path.display())]
    File { path: PathBuf, message: String },
}
