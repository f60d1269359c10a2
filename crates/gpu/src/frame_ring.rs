use std::sync::mpsc::{channel, Receiver, Sender};

use crate::mapped_frame::MappedFrame;
use crate::{FrameReadback, FrameTextures, GpuContext, GpuError};

/// A frame read back from the GPU, its staging buffers still mapped: whoever takes it unpacks
/// its images (on its own threads), which hands the buffers back to the ring.
pub struct ReadFrame {
    pub index: usize,
    /// Its depth half is `None` when the ring was made without depth, its mask without masks.
    pub images: MappedFrame,
}

struct Pending {
    index: usize,
    submission: wgpu::SubmissionIndex,
    readback: FrameReadback,
}

struct Slot {
    textures: FrameTextures,
    pending: Option<Pending>,
}

/// Several frames in flight: frame `i` is drawn into the textures of slot `i % n`, made once and
/// reused. Its readback copy goes into staging buffers lent until the frame's images are
/// unpacked, so the frame loop records the next frames while other threads unpack and encode.
/// The ring makes `2n + 1` sets of them once: for the `n` frames in flight, the one being
/// recorded, and up to `n` frames handed out but not yet unpacked; with more than that still
/// out, it waits for one to come back.
pub struct FrameRing {
    slots: Vec<Slot>,
    free: Receiver<FrameReadback>,
    home: Sender<FrameReadback>,
}

impl FrameRing {
    pub fn new(
        ctx: &GpuContext,
        width: u32,
        height: u32,
        in_flight: usize,
        (with_depth, with_mask): (bool, bool),
    ) -> Self {
        let in_flight = in_flight.max(1);
        let slots = (0..in_flight)
            .map(|_| Slot {
                textures: FrameTextures::with_mask(ctx, width, height, with_mask),
                pending: None,
            })
            .collect();
        let (home, free) = channel();
        for _ in 0..2 * in_flight + 1 {
            // The receiver is alive: it is in `free`.
            let readback = FrameReadback::with_mask(ctx, width, height, with_depth, with_mask);
            let _ = home.send(readback);
        }
        Self { slots, free, home }
    }

    /// Records frame `index` through `record` (render, perturb …) followed by the readback copy,
    /// submits it, and returns the frame that previously occupied the slot, if any.
    pub fn submit<E: From<GpuError>>(
        &mut self,
        ctx: &GpuContext,
        index: usize,
        record: impl FnOnce(&mut wgpu::CommandEncoder, &FrameTextures) -> Result<(), E>,
    ) -> Result<Option<ReadFrame>, E> {
        let readback = self.free.recv().map_err(|_| GpuError::Readback {
            message: "the ring's staging buffers were lost".into(),
        })?;
        let n = self.slots.len();
        let slot = &mut self.slots[index % n];
        // The GPU runs submissions in order: this frame's drawing into the slot's textures
        // starts after the previous frame's copy out of them.
        let previous = slot.pending.take();
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        record(&mut encoder, &slot.textures)?;
        readback.encode_copy(&mut encoder, &slot.textures);
        let submission = ctx.queue.submit([encoder.finish()]);
        ctx.check()?;
        slot.pending = Some(Pending {
            index,
            submission,
            readback,
        });
        Ok(match previous {
            Some(pending) => Some(self.map(ctx, pending)?),
            None => None,
        })
    }

    /// Reads back every frame still in flight, oldest first.
    pub fn drain(&mut self, ctx: &GpuContext) -> Result<Vec<ReadFrame>, GpuError> {
        let mut pending: Vec<Pending> = self
            .slots
            .iter_mut()
            .filter_map(|s| s.pending.take())
            .collect();
        pending.sort_by_key(|p| p.index);
        pending.into_iter().map(|p| self.map(ctx, p)).collect()
    }

    fn map(&self, ctx: &GpuContext, pending: Pending) -> Result<ReadFrame, GpuError> {
        let images = pending
            .readback
            .into_mapped(ctx, pending.submission, self.home.clone())?;
        Ok(ReadFrame {
            index: pending.index,
            images,
        })
    }
}
