use rslam_core::printable;
use rslam_gpu::GpuError;

/// Errors of the perturbation crate.
#[derive(Debug, thiserror::Error)]
pub enum PerturbError {
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// A malformed or unknown item of a spec string.
    #[error("spec item '{item}': {message}")]
    Spec { item: String, message: String },
    /// A perturbation that cannot run on these frames (e.g. a frame too small for it).
    #[error("perturbation '{name}': {message}")]
    Unsupported { name: String, message: String },
    /// A stream or trajectory operation given input it cannot work on.
    #[error("{operation}: {message}")]
    Stream { operation: String, message: String },
}

impl PerturbError {
    pub fn spec(item: impl Into<String>, message: impl Into<String>) -> Self {
        // The item and the message quote what was typed, line breaks included.
        Self::Spec {
            item: printable(&item.into()),
            message: printable(&message.into()),
        }
    }
}
