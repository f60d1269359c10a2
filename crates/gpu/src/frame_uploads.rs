//! Decoded frames uploaded from the threads that decoded them: each frame is written, already in
//! the textures' layout (RGBA rows and depth rows padded for the copy), into GPU buffers through
//! the queue's staging memory on its decoding thread; the frame loop's thread only records the
//! copies into the frame's textures.

use std::num::NonZeroU64;
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::{Arc, Mutex};

use rslam_core::{DepthImage, RgbImage};

use crate::{FrameTextures, GpuContext, GpuError};

/// The frame loop's end: lends buffers to [`UploadFiller`]s and records their copies.
pub struct FrameUploads {
    filler: UploadFiller,
    /// The frame recorded last; its buffers go back once the next one is recorded.
    last: Option<FilledUpload>,
}

impl FrameUploads {
    /// `count` sets of buffers for `width × height` frames: at least as many as frames can be
    /// decoded and waiting at once, plus the two the loop holds, or a decoding thread waits for
    /// a buffer that only a frame it has not decoded yet would free.
    pub fn new(ctx: &GpuContext, width: u32, height: u32, with_depth: bool, count: usize) -> Self {
        let (home, free) = channel();
        let row_bytes = crate::readback::padded_row_bytes(width);
        let size = row_bytes as u64 * height as u64;
        let make = |label| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        for _ in 0..count {
            let buffers = UploadBuffers {
                color: make("upload colour"),
                depth: with_depth.then(|| make("upload depth")),
            };
            // The receiver is alive: it is in `free`.
            let _ = home.send(buffers);
        }
        let shared = Shared {
            queue: ctx.queue.clone(),
            free: Mutex::new(free),
            home,
            width,
            height,
            row_bytes,
        };
        Self {
            filler: UploadFiller {
                shared: Arc::new(shared),
            },
            last: None,
        }
    }

    /// What decoding threads fill frames with.
    pub fn filler(&self) -> UploadFiller {
        self.filler.clone()
    }

    /// Records the copies of `upload` into `frame`'s textures (depth only where it was filled).
    /// The frame recorded by the call before must have been submitted since: its buffers are
    /// lent again now, and writes into them are queued behind that submission.
    pub fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        upload: FilledUpload,
    ) {
        let shared = &self.filler.shared;
        let layout = wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(shared.row_bytes),
            rows_per_image: Some(shared.height),
        };
        let depth = upload.buffers.depth.as_ref().filter(|_| upload.with_depth);
        let copies = [(&upload.buffers.color, &frame.color)]
            .into_iter()
            .chain(depth.map(|buffer| (buffer, &frame.depth)));
        for (buffer, texture) in copies {
            encoder.copy_buffer_to_texture(
                wgpu::TexelCopyBufferInfo { buffer, layout },
                texture.as_image_copy(),
                frame.size(),
            );
        }
        self.last = Some(upload);
    }
}

/// The decoding threads' end: writes a decoded frame into free buffers.
#[derive(Clone)]
pub struct UploadFiller {
    shared: Arc<Shared>,
}

impl UploadFiller {
    /// Writes `color` (as RGBA) and `depth` into free buffers, waiting for one; both must be of
    /// the frames' size.
    pub fn fill(
        &self,
        color: &RgbImage,
        depth: Option<&DepthImage>,
    ) -> Result<FilledUpload, GpuError> {
        let s = &self.shared;
        let sizes =
            std::iter::once((color.width, color.height)).chain(depth.map(|d| (d.width, d.height)));
        if let Some((w, h)) = sizes.into_iter().find(|&size| size != (s.width, s.height)) {
            return Err(upload_failed(format!(
                "a {w}x{h} image into {}x{} frames",
                s.width, s.height
            )));
        }
        let buffers = s
            .free
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .recv()
            .map_err(|_| upload_failed("the upload buffers were lost"))?;
        // From here on the buffers go back when `upload` drops, written or not.
        let upload = FilledUpload {
            buffers,
            with_depth: depth.is_some(),
            home: s.home.clone(),
        };
        let width = s.width as usize;
        // Alpha stays as the row starts: opaque.
        s.write_rows(&upload.buffers.color, |y, row| {
            let rgb = &color.data[y * width * 3..(y + 1) * width * 3];
            for (to, from) in row.chunks_exact_mut(4).zip(rgb.chunks_exact(3)) {
                to[..3].copy_from_slice(from);
            }
        })?;
        if let (Some(depth), Some(buffer)) = (depth, &upload.buffers.depth) {
            s.write_rows(buffer, |y, row| {
                row.copy_from_slice(bytemuck::cast_slice(
                    &depth.data[y * width..(y + 1) * width],
                ));
            })?;
        }
        Ok(upload)
    }
}

/// A frame written into lent buffers, for [`FrameUploads::record`]; its buffers go back for the
/// next frames when it is dropped (by the record after its own, or unrecorded).
pub struct FilledUpload {
    buffers: UploadBuffers,
    with_depth: bool,
    home: Sender<UploadBuffers>,
}

impl Drop for FilledUpload {
    fn drop(&mut self) {
        // Uploads outliving their `FrameUploads` have nowhere to go back to.
        let _ = self.home.send(self.buffers.clone());
    }
}

#[derive(Clone)]
struct UploadBuffers {
    color: wgpu::Buffer,
    depth: Option<wgpu::Buffer>,
}

struct Shared {
    queue: wgpu::Queue,
    free: Mutex<Receiver<UploadBuffers>>,
    home: Sender<UploadBuffers>,
    width: u32,
    height: u32,
    row_bytes: u32,
}

impl Shared {
    /// Queues a write of every row of `buffer` (4 bytes a pixel), row `y` made by
    /// `make_row(y, row)` in a row that keeps what the row before left, all 255 at first.
    fn write_rows(
        &self,
        buffer: &wgpu::Buffer,
        make_row: impl Fn(usize, &mut [u8]),
    ) -> Result<(), GpuError> {
        let size = NonZeroU64::new(buffer.size()).ok_or_else(|| upload_failed("an empty frame"))?;
        let mut staging = self
            .queue
            .write_buffer_with(buffer, 0, size)
            .ok_or_else(|| upload_failed("no staging memory for a frame"))?;
        let stride = self.row_bytes as usize;
        let mut row = vec![u8::MAX; self.width as usize * 4];
        for y in 0..self.height as usize {
            make_row(y, &mut row);
            staging
                .slice(y * stride..y * stride + row.len())
                .copy_from_slice(&row);
        }
        Ok(())
    }
}

fn upload_failed(message: impl Into<String>) -> GpuError {
    GpuError::Upload {
        message: message.into(),
    }
}
