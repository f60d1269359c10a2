/// Errors of the GPU layer.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error("no Vulkan adapter found ({detail}); install a Vulkan driver, e.g. `apt-get install mesa-vulkan-drivers libvulkan1` for lavapipe (CPU)")]
    NoAdapter { detail: String },
    #[error("--adapter '{wanted}' matches no adapter; available: {available}")]
    AdapterNotFound { wanted: String, available: String },
    #[error("could not open the device on adapter '{adapter}': {message}")]
    Device { adapter: String, message: String },
    #[error("shader '{path}': {message}")]
    Shader { path: String, message: String },
    #[error("GPU error: {message}")]
    Validation { message: String },
    #[error("GPU readback failed: {message}")]
    Readback { message: String },
    #[error("GPU upload failed: {message}")]
    Upload { message: String },
}
