//! The frame loop shared by rendering and perturbing: every source frame goes through the ring
//! (record → submit → one readback) and on to a consumer, with progress.

use rslam_gpu::{FrameRing, FrameTextures, GpuContext, ReadFrame};

use super::progress::Progress;
use super::sink::FrameSink;

/// Frames in flight between recording and readback.
const FRAMES_IN_FLIGHT: usize = 3;

/// The GPU side of one run of equally sized frames.
pub struct FrameRun<'a> {
    pub ctx: &'a GpuContext,
    pub width: u32,
    pub height: u32,
    /// Source frame indices, in the order they are recorded and delivered.
    pub sources: &'a [usize],
    /// Read depth back as well as colour.
    pub with_depth: bool,
}

impl FrameRun<'_> {
    /// Records each source frame with `record` and hands its read-back frame to `deliver`, in
    /// order, advancing `progress`.
    pub fn run(
        &self,
        progress: &Progress,
        mut record: impl FnMut(
            usize,
            &mut rslam_gpu::wgpu::CommandEncoder,
            &FrameTextures,
        ) -> anyhow::Result<()>,
        mut deliver: impl FnMut(ReadFrame) -> anyhow::Result<()>,
    ) -> anyhow::Result<()> {
        let mut ring = FrameRing::new(
            self.ctx,
            self.width,
            self.height,
            FRAMES_IN_FLIGHT,
            self.with_depth,
        );
        let mut deliver = |frame| -> anyhow::Result<()> {
            deliver(frame)?;
            progress.advance()
        };
        for &source in self.sources {
            let finished = ring.submit(self.ctx, source, |encoder, frame| {
                record(source, encoder, frame)
            })?;
            if let Some(frame) = finished {
                deliver(frame)?;
            }
        }
        for frame in ring.drain(self.ctx)? {
            deliver(frame)?;
        }
        Ok(())
    }
}

/// Runs every source frame `sink` needs through `record` and into the sink; returns the frames
/// per second achieved.
pub fn drive(
    ctx: &GpuContext,
    sink: &FrameSink,
    with_depth: bool,
    what: &str,
    record: impl FnMut(
        usize,
        &mut rslam_gpu::wgpu::CommandEncoder,
        &FrameTextures,
    ) -> anyhow::Result<()>,
) -> anyhow::Result<f64> {
    let k = sink.intrinsics();
    let sources = sink.plan().needed_sources();
    let progress = Progress::new(sources.len(), what);
    FrameRun {
        ctx,
        width: k.width,
        height: k.height,
        sources: &sources,
        with_depth,
    }
    .run(&progress, record, |frame| {
        sink.accept(frame.index, frame.color, frame.depth)
    })?;
    progress.finish();
    Ok(progress.rate())
}
