//! One source and its perturbations on the GPU: every source frame asked for is recorded,
//! perturbed in the same command encoder, read back once and handed to a sink.

use rslam_gpu::GpuContext;
use rslam_perturb::{PerturbSpec, Perturber};

use crate::frame_loop::FrameRun;
use crate::progress::Progress;
use crate::sink::FrameSink;
use crate::source::FrameSource;
use crate::PipelineError;

pub struct Pipeline<S> {
    source: S,
    perturber: Perturber,
}

impl<S: FrameSource> Pipeline<S> {
    /// Builds the image and depth corruptions of `spec` for the source's frame size.
    pub fn new(
        ctx: &GpuContext,
        source: S,
        spec: &PerturbSpec,
        seed: u64,
    ) -> Result<Self, PipelineError> {
        let (width, height) = source.size();
        let perturber = Perturber::new(ctx, spec, width, height, seed)?;
        Ok(Self { source, perturber })
    }

    pub fn source(&self) -> &S {
        &self.source
    }

    /// Replaces the source; the caller keeps the frame size the perturbations were built for.
    pub(crate) fn set_source(&mut self, source: S) {
        self.source = source;
    }

    /// Runs source frames `sources` (in that order) into `sink`, reporting to `progress`.
    pub fn run(
        &mut self,
        ctx: &GpuContext,
        sources: &[usize],
        progress: &dyn Progress,
        sink: &mut dyn FrameSink,
    ) -> Result<(), PipelineError> {
        let (width, height) = self.source.size();
        self.source.prepare(sources)?;
        let (source, perturber) = (&mut self.source, &mut self.perturber);
        FrameRun {
            ctx,
            width,
            height,
            sources,
            with_depth: source.has_depth(),
        }
        .run(
            progress,
            |index, encoder, frame| {
                source.record(ctx, encoder, frame, index)?;
                perturber.encode(ctx, encoder, frame, index as u32)?;
                Ok(())
            },
            |frame| sink.accept(frame.index, frame.color, frame.depth),
        )
    }
}
