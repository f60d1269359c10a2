//! One camera of a recorded EuRoC dataset as a frame source: its PNGs decoded ahead of the GPU,
//! grey frames widened to the RGB the frame textures take (R = G = B, so a grey frame written
//! back grey is the same bytes). A 16-bit grey camera's frames (TUM-VI's) are taken at their
//! high byte, as OpenCV reads them into 8 bits: the GPU frames are 8-bit.

use std::path::Path;

use rslam_core::dataset::euroc::{CameraColour, EurocFrame};
use rslam_core::dataset::{read_grey16_high_byte, read_rgb8};
use rslam_core::{Intrinsics, RgbImage};
use rslam_gpu::{wgpu, FrameTextures, GpuContext};

use crate::source::{check_in_range, FrameSource};
use crate::upload_ahead::UploadAhead;
use crate::PipelineError;

/// The frames of one `mav0/camN/` folder, in time order; source frame `i` is `frames[i]`.
pub struct EurocCameraSource {
    frames: Vec<EurocFrame>,
    intrinsics: Intrinsics,
    colour: CameraColour,
    /// Each needed frame's colour, decoded ahead into upload buffers.
    frames_ahead: UploadAhead,
}

impl EurocCameraSource {
    pub fn new(frames: Vec<EurocFrame>, intrinsics: Intrinsics, colour: CameraColour) -> Self {
        Self {
            frames,
            intrinsics,
            colour,
            frames_ahead: UploadAhead::new(intrinsics.width, intrinsics.height, false),
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
        let camera = self.intrinsics;
        self.frames_ahead.start(ctx, needed, move |frame, filler| {
            let color = read(&frame.path)?;
            check_size(&frame.path, &color, camera)?;
            Ok(filler.fill(&color, None)?)
        });
        Ok(())
    }

    fn record(
        &mut self,
        _ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        index: usize,
    ) -> Result<(), PipelineError> {
        self.frames_ahead.record(encoder, frame, index)
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
