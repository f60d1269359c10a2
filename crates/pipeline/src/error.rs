use std::path::PathBuf;

use rslam_core::CoreError;
use rslam_gpu::GpuError;
use rslam_perturb::PerturbError;
use rslam_render::RenderError;

/// Errors of a generation run; each names the file, option or frame that was wrong.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    #[error(transparent)]
    Core(#[from] CoreError),
    #[error(transparent)]
    Gpu(#[from] GpuError),
    #[error(transparent)]
    Perturb(#[from] PerturbError),
    #[error(transparent)]
    Render(#[from] RenderError),
    /// A job option that cannot work (`option` is the user-facing name, e.g. `--frames`).
    #[error("{option}: {message}")]
    Option { option: String, message: String },
    /// An input file or folder that cannot be used as it is.
    #[error("{}: {message}", path.display())]
    Input { path: PathBuf, message: String },
    /// An output folder that this run may not write into.
    #[error("{}: {message}", path.display())]
    Output { path: PathBuf, message: String },
    /// An output folder that holds (part of) another job's output; `--force` starts over.
    #[error("{}: {message}", path.display())]
    OtherJob { path: PathBuf, message: String },
    #[error(
        "interrupted: the output is incomplete (no rslam.json written); run the same command again to resume"
    )]
    Interrupted,
    #[error("an encoder thread stopped: {0}")]
    Worker(String),
}

impl PipelineError {
    pub fn option(option: impl Into<String>, message: impl Into<String>) -> Self {
        Self::Option {
            option: option.into(),
            message: message.into(),
        }
    }

    pub fn input(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        Self::Input {
            path: path.into(),
            message: message.into(),
        }
    }

    pub fn output(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        Self::Output {
            path: path.into(),
            message: message.into(),
        }
    }
}
