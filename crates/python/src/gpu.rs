//! The process's one GPU context, created on first use (lavapipe when there is no GPU) and shared
//! by every call; a failure to create it is kept and raised again on each later call.

use std::sync::OnceLock;

use pyo3::exceptions::PyRuntimeError;
use pyo3::PyResult;
use rslam_gpu::{AdapterChoice, GpuContext};

static CONTEXT: OnceLock<Result<GpuContext, String>> = OnceLock::new();

/// The context, created now if this is the first call. Call it with the GIL released.
pub fn context() -> Result<&'static GpuContext, String> {
    CONTEXT
        .get_or_init(|| GpuContext::new(&AdapterChoice::default()).map_err(|e| e.to_string()))
        .as_ref()
        .map_err(|e| format!("no GPU context: {e}"))
}

/// The adapter's description, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) (Cpu, ...)".
pub fn describe() -> PyResult<String> {
    context()
        .map(|c| c.describe())
        .map_err(PyRuntimeError::new_err)
}
