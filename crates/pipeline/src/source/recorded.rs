//! Frames recorded on disk as a layout's reader found them — a Replica or TUM dataset's colour
//! and depth images, or one camera of a EuRoC or TUM-VI recording — decoded ahead of the GPU on
//! worker threads into upload buffers.

use std::path::{Path, PathBuf};

use rslam_core::dataset::euroc::{CameraColour, EurocCameraFrames};
use rslam_core::dataset::{
    decode_depth_png, read_grey16_high_byte, read_rgb, read_rgb8, SourceDataset,
};
use rslam_core::{CoreError, Intrinsics, RgbImage};
use rslam_gpu::{wgpu, FrameTextures, GpuContext};

use crate::source::{check_in_range, FrameSource};
use crate::upload_ahead::UploadAhead;
use crate::PipelineError;

/// One recorded frame's files.
#[derive(Clone, Debug)]
pub struct RecordedFrame {
    pub colour: PathBuf,
    pub depth: Option<PathBuf>,
}

/// How a layout's colour files become the 8-bit RGB of the GPU frames.
pub type ColourReader = fn(&Path) -> Result<RgbImage, CoreError>;

/// Source frame `i` is `frames[i]`, seen by `camera`.
pub struct RecordedSource {
    frames: Vec<RecordedFrame>,
    camera: Intrinsics,
    read_colour: ColourReader,
    /// Metres per depth PNG unit.
    depth_scale: f64,
    /// Whose frames these are, for errors: "the dataset", "cam1".
    whose: String,
    /// Each needed frame, decoded ahead into upload buffers.
    frames_ahead: UploadAhead,
}

impl RecordedSource {
    pub fn new(
        frames: Vec<RecordedFrame>,
        camera: Intrinsics,
        read_colour: ColourReader,
        depth_scale: f64,
        whose: &str,
    ) -> Self {
        let any_depth = frames.iter().any(|f| f.depth.is_some());
        Self {
            frames,
            camera,
            read_colour,
            depth_scale,
            whose: whose.to_string(),
            frames_ahead: UploadAhead::new(camera.width, camera.height, any_depth),
        }
    }

    /// A Replica or TUM dataset's frames, colour and depth.
    pub fn dataset(dataset: &SourceDataset) -> Self {
        let frames = dataset
            .frames
            .iter()
            .map(|f| RecordedFrame {
                colour: f.rgb.clone(),
                depth: f.depth.clone(),
            })
            .collect();
        let scale = dataset.format.depth_scale();
        Self::new(frames, dataset.intrinsics, read_rgb, scale, "the dataset")
    }

    /// One camera of a EuRoC (or TUM-VI) recording: grey frames widened to RGB (R = G = B, so a
    /// grey frame written back grey is the same bytes), 16-bit grey ones (TUM-VI's) at their high
    /// byte as OpenCV reads them into 8 bits; no depth.
    pub fn euroc_camera(camera: &EurocCameraFrames) -> Self {
        let frames = camera
            .frames
            .iter()
            .map(|f| RecordedFrame {
                colour: f.path.clone(),
                depth: None,
            })
            .collect();
        let read: ColourReader = match camera.camera.colour {
            CameraColour::Grey16 => read_grey16_high_byte,
            CameraColour::Grey | CameraColour::Rgb => read_rgb8,
        };
        let name = &camera.camera.name;
        Self::new(frames, camera.camera.intrinsics, read, 1.0, name)
    }
}

impl FrameSource for RecordedSource {
    fn size(&self) -> (u32, u32) {
        (self.camera.width, self.camera.height)
    }

    fn has_depth(&self) -> bool {
        self.frames.iter().all(|f| f.depth.is_some())
    }

    fn camera(&self) -> Option<Intrinsics> {
        Some(self.camera)
    }

    fn prepare(&mut self, ctx: &GpuContext, sources: &[usize]) -> Result<(), PipelineError> {
        let whose = format!("frames of {}", self.whose);
        check_in_range(sources, self.frames.len(), &whose)?;
        let needed: Vec<(usize, RecordedFrame)> = sources
            .iter()
            .map(|&s| (s, self.frames[s].clone()))
            .collect();
        let (read_colour, scale, camera) = (self.read_colour, self.depth_scale, self.camera);
        let whose = self.whose.clone();
        self.frames_ahead.start(ctx, needed, move |frame, filler| {
            let colour = read_colour(&frame.colour)?;
            check_size(&frame.colour, (colour.width, colour.height), camera, &whose)?;
            let depth = match &frame.depth {
                Some(path) => {
                    let depth = decode_depth_png(path, scale)?;
                    check_size(path, (depth.width, depth.height), camera, &whose)?;
                    Some(depth)
                }
                None => None,
            };
            Ok(filler.fill(&colour, depth.as_ref())?)
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

fn check_size(
    path: &Path,
    (width, height): (u32, u32),
    camera: Intrinsics,
    whose: &str,
) -> Result<(), PipelineError> {
    if (width, height) == (camera.width, camera.height) {
        return Ok(());
    }
    Err(PipelineError::input(
        path,
        format!(
            "image is {width}x{height}, but the camera of {whose} is {}x{}",
            camera.width, camera.height
        ),
    ))
}
