//! One rig camera's read-back frames into the EuRoC writer or a rig's ROS 2 bag, encoded on a
//! worker thread while the GPU renders on.

use std::sync::Arc;

use rslam_core::dataset::euroc::EurocWriter;
use rslam_core::dataset::ros2::RigBag;
use rslam_core::dataset::Manifest;
use rslam_core::{CoreError, ImagePool, MaskImage, RgbImage};
use rslam_gpu::MappedFrame;

use crate::encoder_pool::EncoderPool;
use crate::sink::FrameSink;
use crate::PipelineError;

/// Where a rig camera's frames go: each camera's frames in stamp order, and where the writer
/// takes them, their instance masks.
pub trait RigFrameWriter: Send + Sync {
    fn write_frame(&self, camera: usize, t_ns: u64, image: &RgbImage) -> Result<(), CoreError>;
    fn writes_masks(&self) -> bool {
        false
    }
    /// Only called when [`RigFrameWriter::writes_masks`].
    fn write_mask(&self, _camera: usize, _t_ns: u64, _mask: &MaskImage) -> Result<(), CoreError> {
        Ok(())
    }
}

impl RigFrameWriter for EurocWriter {
    fn write_frame(&self, camera: usize, t_ns: u64, image: &RgbImage) -> Result<(), CoreError> {
        self.write_frame_ns(camera, t_ns, image)
    }

    fn writes_masks(&self) -> bool {
        self.has_masks()
    }

    fn write_mask(&self, camera: usize, t_ns: u64, mask: &MaskImage) -> Result<(), CoreError> {
        EurocWriter::write_mask(self, camera, t_ns, mask)
    }
}

impl RigFrameWriter for RigBag {
    fn write_frame(&self, camera: usize, t_ns: u64, image: &RgbImage) -> Result<(), CoreError> {
        RigBag::write_frame(self, camera, t_ns, image)
    }
}

/// Hands source frame `i` of camera `camera` to its writer at `times_ns[i]`.
/// The writer wants each camera's frames in time order, so each camera has one encoder thread of
/// its own (frames of different cameras are encoded side by side); depth is not read back.
pub struct RigCameraSink {
    writer: Arc<dyn RigFrameWriter>,
    camera: usize,
    times_ns: Arc<Vec<u64>>,
    pool: EncoderPool,
    /// Images handed back once written.
    images: Arc<ImagePool>,
}

impl RigCameraSink {
    pub fn new(writer: Arc<dyn RigFrameWriter>, camera: usize, times_ns: Vec<u64>) -> Self {
        Self {
            writer,
            camera,
            times_ns: Arc::new(times_ns),
            // One worker keeps the frames in order; a queue of four lets the GPU run ahead.
            pool: EncoderPool::new(1, 4),
            images: Arc::default(),
        }
    }

    /// Waits for the camera's frames to be on disk; the first error of any of them.
    pub fn finish(self) -> Result<(), PipelineError> {
        self.pool.finish()
    }
}

/// Per camera of `writer`, the frames it keeps of an unfinished run of the same job (none unless
/// `keep`), its frames to be stamped `stamps[camera]`; and how many frames are left to make.
pub fn frames_kept(
    writer: &EurocWriter,
    stamps: &[Vec<u64>],
    keep: bool,
) -> Result<(Vec<usize>, usize), PipelineError> {
    let kept = stamps
        .iter()
        .enumerate()
        .map(|(camera, times_ns)| match keep {
            true => writer.keep_written_frames(camera, times_ns),
            false => Ok(0),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let left = stamps.iter().zip(&kept).map(|(s, k)| s.len() - k).sum();
    Ok((kept, left))
}

/// The writer's checksums and manifest, once every camera's sink has finished with it.
pub fn finish_writer(
    writer: Arc<EurocWriter>,
    manifest: Manifest,
) -> Result<Manifest, PipelineError> {
    let writer = Arc::try_unwrap(writer)
        .map_err(|_| PipelineError::Worker("EuRoC writer still shared".into()))?;
    Ok(writer.finish(manifest)?)
}

impl FrameSink for RigCameraSink {
    /// EuRoC cameras have no depth.
    fn wants_depth(&self) -> bool {
        false
    }

    fn wants_mask(&self) -> bool {
        self.writer.writes_masks()
    }

    fn accept(&mut self, source: usize, frame: MappedFrame) -> Result<(), PipelineError> {
        let Some(&t_ns) = self.times_ns.get(source) else {
            return Err(PipelineError::Worker(format!(
                "camera {}: frame {source} has no timestamp",
                self.camera
            )));
        };
        let (writer, camera, images) = (self.writer.clone(), self.camera, self.images.clone());
        let (color, mask) = (frame.color, frame.mask);
        self.pool.submit(move || {
            // The mask first: a frame kept by a resumed run has its mask.
            if let Some(mask) = mask {
                writer.write_mask(camera, t_ns, &mask.unpack()?)?;
            }
            let color = color.unpack(&images)?;
            writer.write_frame(camera, t_ns, &color)?;
            images.give_rgb(color);
            Ok(())
        })
    }
}
