//! Library errors as Python exceptions, each with the library's one-line message: what the caller
//! got wrong is a `ValueError`, what failed on the GPU or on disk a `RuntimeError` (`OSError`
//! for files).

use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::PyErr;
use rslam_core::CoreError;
use rslam_eval::EvalError;
use rslam_perturb::PerturbError;
use rslam_pipeline::PipelineError;

pub fn pipeline(e: PipelineError) -> PyErr {
    match e {
        PipelineError::Perturb(p) => perturb(p),
        PipelineError::Core(c) => core(c),
        PipelineError::Option { .. } => PyValueError::new_err(e.to_string()),
        PipelineError::Input { .. } => PyOSError::new_err(e.to_string()),
        _ => PyRuntimeError::new_err(e.to_string()),
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
