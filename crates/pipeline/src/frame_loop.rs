//! The frame loop: every source frame is recorded (drawn or uploaded, then perturbed), read back
//! once through the ring of frames in flight, and delivered in order.

use rslam_gpu::{wgpu, FrameRing, FrameTextures, GpuContext, ReadFrame};

use crate::progress::Progress;
use crate::PipelineError;

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
    /// Frames carry an instance mask, read back too.
    pub with_mask: bool,
}

impl FrameRun<'_> {
    /// Records each source frame with `record` and hands its read-back frame to `deliver`, in
    /// order, advancing `progress` after each delivery.
    pub fn run(
        &self,
        progress: &dyn Progress,
        mut record: impl FnMut(
            usize,
            &mut wgpu::CommandEncoder,
            &FrameTextures,
        ) -> Result<(), PipelineError>,
        mut deliver: impl FnMut(ReadFrame) -> Result<(), PipelineError>,
    ) -> Result<(), PipelineError> {
        let mut ring = FrameRing::new(
            self.ctx,
            self.width,
            self.height,
            FRAMES_IN_FLIGHT,
            (self.with_depth, self.with_mask),
        );
        let mut deliver = |frame| -> Result<(), PipelineError> {
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
