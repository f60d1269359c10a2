//! The `rslam` Python module (`rslam._rslam`, wrapped by the package in `python/rslam/`): a thin
//! PyO3 layer over the library crates — argument checks, numpy ↔ buffer conversion, errors as
//! Python exceptions with the library's message.
//!
//! Data flow: numpy arrays are checked and read into `RgbImage` / `DepthImage` buffers
//! ([`arrays`]); with the GIL released, [`frames`] hands them to the pipeline's in-memory API
//! (`FramesInMemory::buffers`, the frame loop `rslam perturb` runs) on the process's one lazily
//! created GPU context ([`gpu`]); output frames come back and are handed to numpy as the Rust
//! buffers themselves. `corrupt` maps the `imagecorruptions` API onto one-item specs and keeps
//! the built GPU work per (name, severity, size, seed); `Perturber` keeps its own. `render` draws
//! a scene along poses through `FramesInMemory::scene_along`; `evaluate_json` is
//! `rslam_eval::evaluate_files`, what `rslam eval --json` prints.

mod arrays;
mod camera;
mod corrupt;
mod errors;
mod eval;
mod frames;
mod gpu;
mod perturber;
mod render;

use pyo3::prelude::*;

/// The GPU adapter rslam uses in this process (created now if not yet), e.g. "llvmpipe (…)"
/// for lavapipe, Mesa's CPU Vulkan driver.
#[pyfunction]
fn gpu_adapter(py: Python<'_>) -> PyResult<String> {
    py.detach(gpu::describe)
}

/// Every perturbation name a spec accepts (image and depth corruptions, then rot, trans, fast,
/// misalign).
#[pyfunction]
fn perturbation_names() -> Vec<&'static str> {
    rslam_perturb::all_names()
}

#[pymodule]
fn _rslam(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(corrupt::corrupt, m)?)?;
    m.add_function(wrap_pyfunction!(corrupt::get_corruption_names, m)?)?;
    m.add_class::<perturber::Perturber>()?;
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    m.add_function(wrap_pyfunction!(render::scene_poses, m)?)?;
    m.add_function(wrap_pyfunction!(eval::evaluate_json, m)?)?;
    m.add_function(wrap_pyfunction!(gpu_adapter, m)?)?;
    m.add_function(wrap_pyfunction!(perturbation_names, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
