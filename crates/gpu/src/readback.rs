use std::sync::mpsc::{self, Sender};

use rslam_core::{DepthImage, ImagePool, MaskImage, RgbImage};

use crate::mapped_frame::MappedFrame;
use crate::{FrameTextures, GpuContext, GpuError};

/// Staging buffers for one frame's colour and, when asked for, its depth and instance mask; rows
/// padded to wgpu's 256-byte alignment.
#[derive(Clone)]
pub struct FrameReadback {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) padded_row_bytes: u32,
    pub(crate) color: wgpu::Buffer,
    pub(crate) depth: Option<wgpu::Buffer>,
    pub(crate) mask: Option<wgpu::Buffer>,
}

/// Colour, depth and mask are 4 bytes per pixel, so one padded row length serves all three (and
/// the uploads, which the same copy alignment applies to).
pub(crate) fn padded_row_bytes(width: u32) -> u32 {
    let unpadded = width * 4;
    let align = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    unpadded.div_ceil(align) * align
}

impl FrameReadback {
    /// Without `with_depth` only colour is copied and read (image-only inputs have no depth).
    pub fn new(ctx: &GpuContext, width: u32, height: u32, with_depth: bool) -> Self {
        Self::with_mask(ctx, width, height, with_depth, false)
    }

    /// Like [`FrameReadback::new`], the instance mask read too when `with_mask` (frames made
    /// with one).
    pub fn with_mask(
        ctx: &GpuContext,
        width: u32,
        height: u32,
        with_depth: bool,
        with_mask: bool,
    ) -> Self {
        let padded = padded_row_bytes(width);
        let make = |label| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: padded as u64 * height as u64,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            })
        };
        Self {
            width,
            height,
            padded_row_bytes: padded,
            color: make("readback colour"),
            depth: with_depth.then(|| make("readback depth")),
            mask: with_mask.then(|| make("readback mask")),
        }
    }

    fn buffers(&self) -> impl Iterator<Item = &wgpu::Buffer> {
        std::iter::once(&self.color)
            .chain(&self.depth)
            .chain(&self.mask)
    }

    /// Records the copies of the textures read back into the staging buffers; a frame without
    /// a mask texture leaves the mask buffer as it was.
    pub fn encode_copy(&self, encoder: &mut wgpu::CommandEncoder, frame: &FrameTextures) {
        let copies = [
            Some((&frame.color, &self.color)),
            self.depth.as_ref().map(|buffer| (&frame.depth, buffer)),
            frame.mask.as_ref().zip(self.mask.as_ref()),
        ];
        for (texture, buffer) in copies.into_iter().flatten() {
            encoder.copy_texture_to_buffer(
                texture.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(self.padded_row_bytes),
                        rows_per_image: Some(self.height),
                    },
                },
                frame.size(),
            );
        }
    }

    /// Waits for `submission`, maps the buffers and unpads them into CPU images; depth is `None`
    /// unless it was asked for.
    pub fn read(
        &self,
        ctx: &GpuContext,
        submission: wgpu::SubmissionIndex,
    ) -> Result<(RgbImage, Option<DepthImage>), GpuError> {
        let (color, depth, _) = self.read_with_mask(ctx, submission)?;
        Ok((color, depth))
    }

    /// [`FrameReadback::read`] with the instance mask, where it was asked for.
    pub fn read_with_mask(
        &self,
        ctx: &GpuContext,
        submission: wgpu::SubmissionIndex,
    ) -> Result<(RgbImage, Option<DepthImage>, Option<MaskImage>), GpuError> {
        // The clone holds the same buffers; it goes back to a ring no one keeps.
        let (home, _) = mpsc::channel();
        let mut frame = self.clone().into_mapped(ctx, submission, home)?;
        let mask = frame.mask.take().map(|m| m.unpack()).transpose()?;
        let (color, depth) = frame.unpack(&ImagePool::default())?;
        Ok((color, depth, mask))
    }

    /// Waits for `submission` and maps the buffers, leaving them mapped: into a frame whose
    /// halves are unpacked wherever it is handed to, and which goes back through `home` then.
    pub(crate) fn into_mapped(
        self,
        ctx: &GpuContext,
        submission: wgpu::SubmissionIndex,
        home: Sender<FrameReadback>,
    ) -> Result<MappedFrame, GpuError> {
        self.map(ctx, submission)?;
        Ok(MappedFrame::new(self, home))
    }

    fn map(&self, ctx: &GpuContext, submission: wgpu::SubmissionIndex) -> Result<(), GpuError> {
        // A failed submission shows up here first, with the real cause.
        ctx.check()?;
        map_and_wait(ctx, self.buffers(), submission)
    }
}

/// `read`'s result over the mapped contents of `buffer`, which is unmapped afterwards.
fn unpack<T>(buffer: &wgpu::Buffer, read: impl FnOnce(&[u8]) -> T) -> Result<T, GpuError> {
    let result = buffer
        .get_mapped_range(..)
        .map(|rows| read(&rows))
        .map_err(readback_failed);
    buffer.unmap();
    result
}

/// Reads a whole buffer (made with `COPY_SRC`) back to the CPU; blocks until the GPU is done.
/// For small logs kept on the GPU during a run and read once at its end.
pub fn read_buffer(ctx: &GpuContext, source: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
    let readback = BufferReadback::new(ctx, source.size());
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    readback.encode_copy(&mut encoder, source, 0);
    let submission = ctx.queue.submit([encoder.finish()]);
    readback.read(ctx, submission)
}

/// A few bytes of a buffer read back to the CPU through one staging buffer, kept for every read:
/// a value computed on the GPU that sizes the next step of a frame.
pub struct BufferReadback {
    staging: wgpu::Buffer,
}

impl BufferReadback {
    /// Reads of `size` bytes.
    pub fn new(ctx: &GpuContext, size: u64) -> Self {
        Self {
            staging: ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("readback buffer"),
                size,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            }),
        }
    }

    /// Records the copy of the bytes of `source` from `offset` (made with `COPY_SRC`).
    pub fn encode_copy(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        source: &wgpu::Buffer,
        offset: u64,
    ) {
        encoder.copy_buffer_to_buffer(source, offset, &self.staging, 0, self.staging.size());
    }

    /// The bytes copied by `submission`; blocks until it has run.
    pub fn read(
        &self,
        ctx: &GpuContext,
        submission: wgpu::SubmissionIndex,
    ) -> Result<Vec<u8>, GpuError> {
        map_and_wait(ctx, [&self.staging], submission)?;
        unpack(&self.staging, <[u8]>::to_vec)
    }
}

/// Reads single texels of 4-byte formats (`Rgba8Unorm`, `R32Float`): each `(texture, x, y)` in
/// order, as its raw bytes. For a pixel readout under a cursor; blocks until the GPU is done.
pub fn read_texels(
    ctx: &GpuContext,
    texels: &[(&wgpu::Texture, u32, u32)],
) -> Result<Vec<[u8; 4]>, GpuError> {
    let stride = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT as u64;
    let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback texels"),
        size: stride * texels.len().max(1) as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    for (i, &(texture, x, y)) in texels.iter().enumerate() {
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d { x, y, z: 0 },
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: stride * i as u64,
                    bytes_per_row: Some(stride as u32),
                    rows_per_image: Some(1),
                },
            },
            wgpu::Extent3d {
                width: 1,
                height: 1,
                depth_or_array_layers: 1,
            },
        );
    }
    let submission = ctx.queue.submit([encoder.finish()]);
    map_and_wait(ctx, [&buffer], submission)?;
    unpack(&buffer, |view| {
        (0..texels.len())
            .map(|i| {
                let at = i * stride as usize;
                [view[at], view[at + 1], view[at + 2], view[at + 3]]
            })
            .collect()
    })
}

pub(crate) fn readback_failed(e: impl std::fmt::Display) -> GpuError {
    GpuError::Readback {
        message: e.to_string(),
    }
}

/// Maps `buffers` for reading once `submission` has run, and waits until they are.
fn map_and_wait<'a>(
    ctx: &GpuContext,
    buffers: impl IntoIterator<Item = &'a wgpu::Buffer>,
    submission: wgpu::SubmissionIndex,
) -> Result<(), GpuError> {
    let (tx, rx) = mpsc::channel();
    let mut mapping = 0;
    for buffer in buffers {
        let tx = tx.clone();
        buffer.map_async(wgpu::MapMode::Read, .., move |r| {
            let _ = tx.send(r);
        });
        mapping += 1;
    }
    ctx.device
        .poll(wgpu::PollType::Wait {
            submission_index: Some(submission),
            timeout: None,
        })
        .map_err(readback_failed)?;
    for _ in 0..mapping {
        rx.recv()
            .map_err(readback_failed)?
            .map_err(readback_failed)?;
    }
    ctx.check()
}

#[cfg(test)]
mod tests {
    use super::padded_row_bytes;

    #[test]
    fn rows_are_padded_to_256_bytes() {
        assert_eq!(padded_row_bytes(64), 256);
        assert_eq!(padded_row_bytes(65), 512);
        assert_eq!(padded_row_bytes(1200), 4864);
    }
}
