//! One camera of a recorded EuRoC dataset as a frame source: its PNGs decoded ahead of the GPU,
//! grey frames widened to the RGB the frame textures take (R = G = B, so a grey frame written
//! back grey is the same bytes). A 16-bit grey camera's frames (TUM-VI's) are taken at their
//! high byte, as OpenCV reads them into 8 bits: the GPU frames are 8-bit.

use std::path::Path;

use rslam_core::dataset::euroc::{CameraColour, EurocFrame};
use rslam_core::dataset::{read_grey16_high_byte, read_rgb8};
use rslam_core::{Intrinsics, RgbImage};
use rslam_gpu::{wgpu, FilledUpload, FrameTextures, FrameUploads, GpuContext};

use crate::decode_ahead::{frame_uploads, next_frame, DecodeAhead};
use crate::source::{check_in_range, FrameSource};
use crate::PipelineError;

/// The frames of one `mav0/camN/` folder, in time order; source frame `i` is `frames[i]`.
pub struct EurocCameraSource {
    frames: Vec<EurocFrame>,
    intrinsics: Intrinsics,
    colour: CameraColour,
    /// Made at the first run, kept for the next.
    uploads: Option<FrameUploads>,
    /// Each needed frame's colour, decoded into upload buffers with its source index.
    decoder: Option<DecodeAhead<(usize, FilledUpload)>>,
}

impl EurocCameraSource {
    pub fn new(frames: Vec<EurocFrame>, intrinsics: Intrinsics, colour: CameraColour) -> Self {
        Self {
            frames,
            intrinsics,
            colour,
            uploads: None,
            decoder: None,
        }
    }
}

impl FrameSource for EurocCameraSource {
    fn size(&self) -> (u32, u32) {
        (self.intrinsics.width, self.intrinsics.height)
    }

    fn has_depth(&self) -> bool {
        false
    }

    fn camera(&self) -> Option<Intrinsics> {
        Some(self.intrinsics)
    }

    fn prepare(&mut self, ctx: &GpuContext, sources: &[usize]) -> Result<(), PipelineError> {
        check_in_range(sources, self.frames.len(), "frames of the camera")?;
        let needed: Vec<(usize, EurocFrame)> = sources
            .iter()
            .map(|&s| (s, self.frames[s].clone()))
            .collect();
        let read = match self.colour {
            CameraColour::Grey16 => read_grey16_high_byte,
            CameraColour::Grey | CameraColour::Rgb => read_rgb8,
        };
        // Dropping the decoder of a run before hands its buffers back.
        self.decoder = None;
        let (width, height) = self.size();
        let filler = self
            .uploads
            .get_or_insert_with(|| frame_uploads(ctx, width, height, false))
            .filler();
        let camera = self.intrinsics;
        self.decoder = Some(DecodeAhead::start(needed, move |(index, frame)| {
            let color = read(&frame.path)?;
            check_size(&frame.path, &color, camera)?;
            Ok((*index, filler.fill(&color, None)?))
        }));
        Ok(())
    }

    fn record(
        &mut self,
        _ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        index: usize,
    ) -> Result<(), PipelineError> {
        let upload = next_frame(self.decoder.as_ref(), index)?;
        let uploads = self
            .uploads
            .as_mut()
            .ok_or_else(|| PipelineError::Worker("frames recorded before prepare".into()))?;
        uploads.record(encoder, frame, upload);
        Ok(())
    }
}

fn check_size(path: &Path, image: &RgbImage, camera: Intrinsics) -> Result<(), PipelineError> {
    if (image.width, image.height) == (camera.width, camera.height) {
        return Ok(());
    }
    Err(PipelineError::input(
        path,
        format!(
            "image is {}x{}, but the camera's calibration says {}x{}",
            image.width, image.height, camera.width, camera.height
        ),
    ))
}
