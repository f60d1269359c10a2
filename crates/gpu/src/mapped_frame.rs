//! A frame read back but not yet unpacked: its staging buffers stay mapped until whoever takes it
//! copies the images out, on its own worker threads, so the frame loop's thread does not spend
//! its time unpacking rows; then the buffers go back to the ring that lent them.

use std::sync::mpsc::Sender;
use std::sync::Arc;

use rslam_core::{DepthImage, ImagePool, MaskImage, RgbImage};

use crate::readback::{readback_failed, FrameReadback};
use crate::GpuError;

/// A frame's staging buffers, mapped, with the colour half and (when read) the depth half and
/// the instance mask.
pub struct MappedFrame {
    pub color: MappedColor,
    pub depth: Option<MappedDepth>,
    pub mask: Option<MappedMask>,
}

impl MappedFrame {
    /// Both halves of a mapped `readback`; it goes back through `home` once neither is mapped.
    pub(crate) fn new(readback: FrameReadback, home: Sender<FrameReadback>) -> Self {
        let (width, height) = (readback.width, readback.height);
        let row_bytes = readback.padded_row_bytes as usize;
        let view = |buffer: &wgpu::Buffer, lent: &Arc<Lent>| MappedBuffer {
            buffer: buffer.clone(),
            width,
            height,
            row_bytes,
            _lent: lent.clone(),
        };
        let (color, depth) = (readback.color.clone(), readback.depth.clone());
        let mask = readback.mask.clone();
        let lent = Arc::new(Lent {
            readback: Some(readback),
            home,
        });
        Self {
            color: MappedColor(view(&color, &lent)),
            depth: depth.map(|buffer| MappedDepth(view(&buffer, &lent))),
            mask: mask.map(|buffer| MappedMask(view(&buffer, &lent))),
        }
    }

    /// Copies both images out into buffers of `images`.
    pub fn unpack(self, images: &ImagePool) -> Result<(RgbImage, Option<DepthImage>), GpuError> {
        let color = self.color.unpack(images)?;
        let depth = self.depth.map(|d| d.unpack(images)).transpose()?;
        Ok((color, depth))
    }
}

/// The colour half: RGBA rows padded to wgpu's copy alignment.
pub struct MappedColor(MappedBuffer);

impl MappedColor {
    /// The colour as an RGB image, in a buffer of `images` where it has one.
    pub fn unpack(self, images: &ImagePool) -> Result<RgbImage, GpuError> {
        let b = &self.0;
        let rows = b.buffer.get_mapped_range(..).map_err(readback_failed)?;
        Ok(images.rgb_from_rgba_rows(b.width, b.height, &rows, b.row_bytes))
    }
}

/// The depth half: f32 rows padded to wgpu's copy alignment.
pub struct MappedDepth(MappedBuffer);

impl MappedDepth {
    /// The depth image, in a buffer of `images` where it has one.
    pub fn unpack(self, images: &ImagePool) -> Result<DepthImage, GpuError> {
        let b = &self.0;
        let rows = b.buffer.get_mapped_range(..).map_err(readback_failed)?;
        Ok(images.depth_from_f32_rows(b.width, b.height, &rows, b.row_bytes))
    }
}

/// The instance mask: u32 rows padded to wgpu's copy alignment.
pub struct MappedMask(MappedBuffer);

impl MappedMask {
    /// The mask, ids as 16-bit values.
    pub fn unpack(self) -> Result<MaskImage, GpuError> {
        let b = &self.0;
        let rows = b.buffer.get_mapped_range(..).map_err(readback_failed)?;
        Ok(MaskImage::from_u32_rows(
            b.width,
            b.height,
            &rows,
            b.row_bytes,
        ))
    }
}

/// One mapped staging buffer; unmapped when dropped, unpacked or not.
struct MappedBuffer {
    buffer: wgpu::Buffer,
    width: u32,
    height: u32,
    row_bytes: usize,
    // Dropped after `drop` below has unmapped the buffer.
    _lent: Arc<Lent>,
}

impl Drop for MappedBuffer {
    fn drop(&mut self) {
        self.buffer.unmap();
    }
}

/// The staging buffers on loan from a ring, sent back when the last half is dropped.
struct Lent {
    readback: Option<FrameReadback>,
    home: Sender<FrameReadback>,
}

impl Drop for Lent {
    fn drop(&mut self) {
        if let Some(readback) = self.readback.take() {
            // A ring that is gone has no more use for it.
            let _ = self.home.send(readback);
        }
    }
}
