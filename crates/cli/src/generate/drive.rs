//! The frame loop shared by rendering and perturbing datasets: every needed source frame goes
//! through the ring (record → submit → one readback) and on to the sink, with progress.

use rslam_gpu::{FrameRing, FrameTextures, GpuContext};

use super::progress::Progress;
use super::sink::FrameSink;

/// Frames in flight between recording and readback.
const FRAMES_IN_FLIGHT: usize = 3;

/// Records each source frame with `record` and hands the read-back frames to `sink`; returns
/// the frames per second achieved.
pub fn drive(
    ctx: &GpuContext,
    sink: &FrameSink,
    with_depth: bool,
    what: &str,
    mut record: impl FnMut(
        usize,
        &mut rslam_gpu::wgpu::CommandEncoder,
        &FrameTextures,
    ) -> anyhow::Result<()>,
) -> anyhow::Result<f64> {
    let k = sink.intrinsics();
    let mut ring = FrameRing::new(ctx, k.width, k.height, FRAMES_IN_FLIGHT);
    let sources = sink.plan().needed_sources();
    let progress = Progress::new(sources.len(), what);
    let deliver = |frame: rslam_gpu::ReadFrame| -> anyhow::Result<()> {
        let depth = with_depth.then_some(frame.depth);
        sink.accept(frame.index, frame.color, depth)?;
        progress.advance()
    };
    for &source in &sources {
        let finished = ring.submit(ctx, source, |encoder, frame| record(source, encoder, frame))?;
        if let Some(frame) = finished {
            deliver(frame)?;
        }
    }
    for frame in ring.drain(ctx)? {
        deliver(frame)?;
    }
    progress.finish();
    Ok(progress.rate())
}
