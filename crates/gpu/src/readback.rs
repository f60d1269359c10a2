use std::sync::mpsc;

use rslam_core::{DepthImage, RgbImage};

use crate::{FrameTextures, GpuContext, GpuError};

/// Staging buffers for one frame's colour and depth, rows padded to wgpu's 256-byte alignment.
pub struct FrameReadback {
    width: u32,
    height: u32,
    padded_row_bytes: u32,
    color: wgpu::Buffer,
    depth: wgpu::Buffer,
}

/// Both colour and depth are 4 bytes per pixel, so one padded row length serves both.
fn padded_row_bytes(width: u32) -> u32 {
    let unpadded = width * 4;
    let align = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    unpadded.div_ceil(align) * align
}

impl FrameReadback {
    pub fn new(ctx: &GpuContext, width: u32, height: u32) -> Self {
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
            depth: make("readback depth"),
        }
    }

    /// Records the copies of both textures into the staging buffers.
    pub fn encode_copy(&self, encoder: &mut wgpu::CommandEncoder, frame: &FrameTextures) {
        for (texture, buffer) in [(&frame.color, &self.color), (&frame.depth, &self.depth)] {
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

    /// Waits for `submission`, maps both buffers and unpads them into CPU images.
    pub fn read(
        &self,
        ctx: &GpuContext,
        submission: wgpu::SubmissionIndex,
    ) -> Result<(RgbImage, DepthImage), GpuError> {
        // A failed submission shows up here first, with the real cause.
        ctx.check()?;
        let (tx, rx) = mpsc::channel();
        for buffer in [&self.color, &self.depth] {
            let tx = tx.clone();
            buffer.map_async(wgpu::MapMode::Read, .., move |r| {
                let _ = tx.send(r);
            });
        }
        ctx.device
            .poll(wgpu::PollType::Wait {
                submission_index: Some(submission),
                timeout: None,
            })
            .map_err(|e| GpuError::Readback {
                message: e.to_string(),
            })?;
        for _ in 0..2 {
            rx.recv()
                .map_err(|e| GpuError::Readback {
                    message: e.to_string(),
                })?
                .map_err(|e| GpuError::Readback {
                    message: e.to_string(),
                })?;
        }
        ctx.check()?;
        let row = (self.width * 4) as usize;
        let unpad = |buffer: &wgpu::Buffer| -> Result<Vec<u8>, GpuError> {
            let view = buffer
                .get_mapped_range(..)
                .map_err(|e| GpuError::Readback {
                    message: e.to_string(),
                })?;
            let mut out = Vec::with_capacity(row * self.height as usize);
            for chunk in view.chunks(self.padded_row_bytes as usize) {
                out.extend_from_slice(&chunk[..row]);
            }
            Ok(out)
        };
        let rgba = unpad(&self.color)?;
        let depth_bytes = unpad(&self.depth)?;
        self.color.unmap();
        self.depth.unmap();
        let color = RgbImage::from_rgba(self.width, self.height, &rgba);
        let depth = DepthImage {
            width: self.width,
            height: self.height,
            data: bytemuck::pod_collect_to_vec(&depth_bytes),
        };
        Ok((color, depth))
    }
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
