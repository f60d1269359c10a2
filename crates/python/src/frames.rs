//! Frames through the pipeline's in-memory API, with the GIL released: `corrupt` and `Perturber`
//! both land here. Perturbations are built once per frame size and reused for later calls.

use rslam_core::{DepthImage, Intrinsics, RgbImage};
use rslam_perturb::PerturbSpec;
use rslam_pipeline::source::{BufferSource, FrameSource};
use rslam_pipeline::{FramesInMemory, PipelineError, RgbdFrame};

use crate::gpu;

/// What can go wrong while the GIL is released; turned into an exception after.
pub enum RunError {
    NoGpu(String),
    Pipeline(PipelineError),
}

impl From<PipelineError> for RunError {
    fn from(e: PipelineError) -> Self {
        Self::Pipeline(e)
    }
}

impl From<RunError> for pyo3::PyErr {
    fn from(e: RunError) -> Self {
        match e {
            RunError::NoGpu(message) => pyo3::exceptions::PyRuntimeError::new_err(message),
            RunError::Pipeline(e) => crate::errors::pipeline(e),
        }
    }
}

/// Runs `frames` (frame `numbers[i]` of the sequence each, taken with `camera` if known) through
/// `spec` with `seed`, reusing the perturbations in `slot` when they were built for this frame
/// size; returns the output frames in order.
pub fn run(
    slot: &mut Option<FramesInMemory<BufferSource>>,
    spec: &PerturbSpec,
    seed: u64,
    frames: Vec<(RgbImage, Option<DepthImage>)>,
    numbers: Vec<usize>,
    camera: Option<Intrinsics>,
) -> Result<Vec<RgbdFrame>, RunError> {
    let ctx = gpu::context().map_err(RunError::NoGpu)?;
    let mut source = BufferSource::at_frames(frames, numbers)?;
    if let Some(camera) = camera {
        source = source.with_camera(camera)?;
    }
    let count = source.len();
    let reusable = slot.as_ref().is_some_and(|f| f.size() == source.size());
    let frames = match slot {
        Some(built) if reusable => {
            built.set_frames(source)?;
            built
        }
        _ => slot.insert(FramesInMemory::buffers(ctx, source, spec, seed)?),
    };
    let mut out = Vec::with_capacity(count);
    frames.frames(ctx, 0..count, |frame| {
        out.push(frame);
        Ok(())
    })?;
    Ok(out)
}
