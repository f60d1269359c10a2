//! Library errors as Python exceptions, each with the library's one-line message: what the caller
//! got wrong is a `ValueError`, what failed on the GPU or on disk a `RuntimeError` (`OSError`
//! for files).

use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::PyErr;
use rslam_core::CoreError;
use rslam_eval::EvalError;
use rslam_perturb::PerturbError;
use rslam_pipeline::PipelineError;
use rslam_render::RenderError;

pub fn pipeline(e: PipelineError) -> PyErr {
    match e {
        PipelineError::Perturb(p) => perturb(p),
        PipelineError::Core(c) => core(c),
        PipelineError::Option { .. } => PyValueError::new_err(e.to_string()),
        PipelineError::Input { .. } => PyOSError::new_err(e.to_string()),
        PipelineError::Render(r) => render(r),
        _ => PyRuntimeError::new_err(e.to_string()),
    }
}

/// A scene, mesh or path that cannot be used is the caller's; the GPU's failures are not.
fn render(e: RenderError) -> PyErr {
    let message = e.to_string();
    match e {
        RenderError::Core(c) => core(c),
        RenderError::Io { .. } => PyOSError::new_err(message),
        RenderError::UnknownScene { .. }
        | RenderError::UnsupportedFormat { .. }
        | RenderError::BadMesh { .. }
        | RenderError::BadTexture { .. }
        | RenderError::Actors { .. } => PyValueError::new_err(message),
        _ => PyRuntimeError::new_err(message),
    }
}

pub fn perturb(e: PerturbError) -> PyErr {
    match e {
        PerturbError::Gpu(_) => PyRuntimeError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

pub fn core(e: CoreError) -> PyErr {
    let message = e.to_string();
    match e {
        CoreError::Io { .. } => PyOSError::new_err(message),
        _ => PyValueError::new_err(message),
    }
}

pub fn eval(e: EvalError) -> PyErr {
    match e {
        EvalError::Core(c) => core(c),
        other => PyValueError::new_err(other.to_string()),
    }
}
