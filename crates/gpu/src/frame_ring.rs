use std::sync::Arc;

use rslam_core::{DepthImage, ImagePool, RgbImage};

use crate::{FrameReadback, FrameTextures, GpuContext, GpuError};

/// A frame read back to the CPU.
pub struct ReadFrame {
    pub index: usize,
    pub color: RgbImage,
    /// `None` when the ring was made without depth.
    pub depth: Option<DepthImage>,
}

struct Slot {
    textures: FrameTextures,
    readback: FrameReadback,
    pending: Option<(usize, wgpu::SubmissionIndex)>,
}

/// Several frames in flight: frame `i` uses slot `i % n`; its textures and staging buffers are
/// allocated once and reused. Submitting into a busy slot first reads the older frame back, into
/// image buffers the ring's pool was handed back where it has them.
pub struct FrameRing {
    slots: Vec<Slot>,
    images: Arc<ImagePool>,
}

impl FrameRing {
    pub fn new(
        ctx: &GpuContext,
        width: u32,
        height: u32,
        in_flight: usize,
        with_depth: bool,
        images: Arc<ImagePool>,
    ) -> Self {
        let slots = (0..in_flight.max(1))
            .map(|_| Slot {
                textures: FrameTextures::new(ctx, width, height),
                readback: FrameReadback::new(ctx, width, height, with_depth),
                pending: None,
            })
            .collect();
        Self { slots, images }
    }

    /// Records frame `index` through `record` (render, perturb …) followed by the readback copy,
    /// submits it, and returns the frame that previously occupied the slot, if any.
    pub fn submit<E: From<GpuError>>(
        &mut self,
        ctx: &GpuContext,
        index: usize,
        record: impl FnOnce(&mut wgpu::CommandEncoder, &FrameTextures) -> Result<(), E>,
    ) -> Result<Option<ReadFrame>, E> {
        let n = self.slots.len();
        let slot = &mut self.slots[index % n];
        let finished = match slot.pending.take() {
            Some((old, submission)) => Some(read_slot(ctx, slot, old, submission, &self.images)?),
            None => None,
        };
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        record(&mut encoder, &slot.textures)?;
        slot.readback.encode_copy(&mut encoder, &slot.textures);
        let submission = ctx.queue.submit([encoder.finish()]);
        ctx.check()?;
        slot.pending = Some((index, submission));
        Ok(finished)
    }

    /// Reads back every frame still in flight, oldest first.
    pub fn drain(&mut self, ctx: &GpuContext) -> Result<Vec<ReadFrame>, GpuError> {
        let mut order: Vec<usize> = (0..self.slots.len())
            .filter(|&i| self.slots[i].pending.is_some())
            .collect();
        order.sort_by_key(|&i| self.slots[i].pending.as_ref().map(|p| p.0));
        let mut frames = Vec::with_capacity(order.len());
        for i in order {
            let slot = &mut self.slots[i];
            if let Some((index, submission)) = slot.pending.take() {
                frames.push(read_slot(ctx, slot, index, submission, &self.images)?);
            }
        }
        Ok(frames)
    }
}

fn read_slot(
    ctx: &GpuContext,
    slot: &Slot,
    index: usize,
    submission: wgpu::SubmissionIndex,
    images: &ImagePool,
) -> Result<ReadFrame, GpuError> {
    let (color, depth) = slot.readback.read_into(ctx, submission, images)?;
    Ok(ReadFrame {
        index,
        color,
        depth,
    })
}
