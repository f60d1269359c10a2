//! One source and its perturbations on the GPU: every source frame asked for is recorded,
//! perturbed in the same command encoder, read back once and handed to a sink.

use rslam_gpu::{wgpu, FrameTextures, GpuContext};
use rslam_perturb::{PerturbSpec, Perturber};

use crate::depth_colormap::DepthRange;
use crate::frame_loop::FrameRun;
use crate::progress::Progress;
use crate::shown_frame::{copy_frame, Held, ShownFrame, ShownSources};
use crate::sink::FrameSink;
use crate::source::FrameSource;
use crate::state_log::StateLog;
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
        let perturber = Perturber::new(ctx, spec, width, height, seed, source.camera())?;
        Ok(Self { source, perturber })
    }

    pub fn perturber(&self) -> &Perturber {
        &self.perturber
    }

    pub fn source(&self) -> &S {
        &self.source
    }

    /// Replaces the source; the caller keeps the frame size the perturbations were built for.
    pub(crate) fn set_source(&mut self, source: S) {
        self.source = source;
    }

    pub fn source_mut(&mut self) -> &mut S {
        &mut self.source
    }

    /// Takes another spec and seed for the frame corruptions: new levels in place when the items
    /// are the same (a severity slider moving), else a new perturber.
    pub fn set_spec(
        &mut self,
        ctx: &GpuContext,
        spec: &PerturbSpec,
        seed: u64,
    ) -> Result<(), PipelineError> {
        if !self.perturber.set_levels(spec, seed) {
            let (width, height) = self.source.size();
            let camera = self.source.camera();
            self.perturber = Perturber::new(ctx, spec, width, height, seed, camera)?;
        }
        Ok(())
    }

    /// The frame loop's record step without its readback, for display: the source frames of one
    /// output frame are drawn by `draw` into `shown` (unless it holds `held` already), copied,
    /// perturbed there, and the depth colour-mapped at `range`. Each source frame is its own
    /// submission, as in the frame loop (uniforms are written at record time).
    pub(crate) fn show_with(
        &mut self,
        ctx: &GpuContext,
        held: Held,
        shown: &mut ShownFrame,
        range: DepthRange,
        mut draw: impl FnMut(
            &mut S,
            &mut wgpu::CommandEncoder,
            &FrameTextures,
            usize,
        ) -> Result<(), PipelineError>,
    ) -> Result<(), PipelineError> {
        let ShownSources { rgb, depth } = held.sources;
        let redraw = shown.held.as_ref() != Some(&held);
        shown.held = None;
        shown.set_has_depth(self.source.has_depth());
        let mut frames = vec![(rgb, &shown.clean, &shown.perturbed)];
        if depth != rgb {
            frames.push((depth, &shown.lagged_clean, &shown.lagged_perturbed));
        }
        if redraw {
            let sources: Vec<usize> = frames.iter().map(|f| f.0).collect();
            self.source.prepare(ctx, &sources)?;
        }
        for (index, clean, perturbed) in frames {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            if redraw {
                draw(&mut self.source, &mut encoder, clean, index)?;
            }
            copy_frame(&mut encoder, clean, perturbed);
            self.perturber
                .encode(ctx, &mut encoder, perturbed, index as u32)?;
            ctx.queue.submit([encoder.finish()]);
        }
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        shown.encode_depth_colors(ctx, &mut encoder, held.sources, range);
        ctx.queue.submit([encoder.finish()]);
        ctx.check()?;
        shown.held = Some(held);
        Ok(())
    }

    /// Runs source frames `sources` (in that order) into `sink`, reporting to `progress`; the
    /// state of stateful perturbations per frame goes to the sink after the last frame.
    pub fn run(
        &mut self,
        ctx: &GpuContext,
        sources: &[usize],
        progress: &dyn Progress,
        sink: &mut dyn FrameSink,
    ) -> Result<(), PipelineError> {
        let (width, height) = self.source.size();
        self.source.prepare(ctx, sources)?;
        let (source, perturber) = (&mut self.source, &mut self.perturber);
        let log = StateLog::new(ctx, perturber, sources);
        let mut position = 0;
        FrameRun {
            ctx,
            width,
            height,
            sources,
            with_depth: source.has_depth() && sink.wants_depth(),
            with_mask: source.has_mask() && sink.wants_mask(),
        }
        .run(
            progress,
            |index, encoder, frame| {
                source.record(ctx, encoder, frame, index)?;
                let got = perturber.encode(ctx, encoder, frame, index as u32)?;
                if let Some(log) = &log {
                    log.encode(encoder, perturber, &got, position);
                }
                position += 1;
                Ok(())
            },
            |frame| sink.accept(frame.index, frame.images),
        )?;
        match log {
            Some(log) => sink.accept_state(log.read(ctx)?),
            None => Ok(()),
        }
    }
}
