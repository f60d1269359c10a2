//! A camera of a recorded ROS 2 bag: its colour and depth messages, read from the bag in file
//! order on the decoding threads and decoded there into upload buffers ahead of the GPU. A depth
//! camera of its own has no colour: its frames' colour plane is left black and never written.

use std::collections::{HashMap, HashSet};
use std::sync::{Arc, Mutex};

use rslam_core::dataset::ros2::{
    decode_colour, decode_depth, BagMessages, RecordedBagCamera, RecordedBagCameras,
};
use rslam_core::{CoreError, Intrinsics, RgbImage};
use rslam_gpu::{wgpu, FrameTextures, GpuContext};

use crate::source::{check_in_range, FrameSource};
use crate::upload_ahead::UploadAhead;
use crate::PipelineError;

/// Source frame `i` is camera `camera`'s colour message `i` and depth message `i`.
pub struct BagSource {
    recorded: Arc<RecordedBagCameras>,
    camera: usize,
    frames_ahead: UploadAhead,
}

impl BagSource {
    pub fn new(recorded: Arc<RecordedBagCameras>, camera: usize) -> Self {
        let spec = &recorded.cameras[camera];
        let (width, height) = spec.frames().size;
        let frames_ahead = UploadAhead::new(width, height, spec.depth.is_some());
        Self {
            recorded,
            camera,
            frames_ahead,
        }
    }

    fn spec(&self) -> &RecordedBagCamera {
        &self.recorded.cameras[self.camera]
    }
}

impl FrameSource for BagSource {
    fn size(&self) -> (u32, u32) {
        self.spec().frames().size
    }

    fn has_depth(&self) -> bool {
        self.spec().depth.is_some()
    }

    fn camera(&self) -> Option<Intrinsics> {
        Some(self.spec().intrinsics)
    }

    fn prepare(&mut self, ctx: &GpuContext, sources: &[usize]) -> Result<(), PipelineError> {
        let camera = self.spec();
        let frames = camera.frames();
        check_in_range(sources, frames.messages.len(), &frames.name)?;
        let (width, height) = frames.size;
        let blank = camera
            .colour
            .is_none()
            .then(|| RgbImage::new(width, height));
        let messages = Mutex::new(CameraMessages {
            messages: self.recorded.bag.messages()?,
            colour_channel: camera.colour.as_ref().map(|c| c.channel),
            depth_channel: camera.depth.as_ref().map(|d| d.channel),
            read: (0, 0),
            wanted: sources.iter().copied().collect(),
            waiting: HashMap::new(),
        });
        let messages = Arc::new(messages);
        let (recorded, camera_index) = (self.recorded.clone(), self.camera);
        let items = sources.iter().map(|&s| (s, s)).collect();
        self.frames_ahead.start(ctx, items, move |&frame, filler| {
            // The decoding threads take frames in order, a few at a time: each reads on in the
            // bag to its own messages, setting aside those of the frames after it.
            let (colour, depth) = messages
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .take(frame)?;
            let camera = &recorded.cameras[camera_index];
            let bad = |topic: &str, e: String| {
                PipelineError::from(CoreError::bad_file(
                    &recorded.bag.folder,
                    format!("topic {topic}: {e}"),
                ))
            };
            let decoded;
            let colour = match (&camera.colour, colour, &blank) {
                (Some(topic), Some(data), _) => {
                    decoded =
                        decode_colour(&data, &topic.encoding).map_err(|e| bad(&topic.name, e))?;
                    &decoded
                }
                (_, _, Some(blank)) => blank,
                _ => {
                    return Err(PipelineError::Worker(format!(
                        "frame {frame} has no colour"
                    )))
                }
            };
            let depth = match (&camera.depth, depth) {
                (Some(topic), Some(data)) => {
                    Some(decode_depth(&data, &topic.encoding).map_err(|e| bad(&topic.name, e))?)
                }
                _ => None,
            };
            Ok(filler.fill(colour, depth.as_ref())?)
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

/// The camera's messages read from the bag in file order.
struct CameraMessages {
    messages: BagMessages,
    colour_channel: Option<u16>,
    depth_channel: Option<u16>,
    /// How many colour and depth messages were read.
    read: (usize, usize),
    /// The source frames the run records.
    wanted: HashSet<usize>,
    /// Messages read ahead of their frame: (frame, is depth) → CDR bytes.
    waiting: HashMap<(usize, bool), Vec<u8>>,
}

type FrameMessages = (Option<Vec<u8>>, Option<Vec<u8>>);

impl CameraMessages {
    /// Source frame `index`'s colour and depth messages (those the camera has).
    fn take(&mut self, index: usize) -> Result<FrameMessages, PipelineError> {
        let (with_colour, with_depth) =
            (self.colour_channel.is_some(), self.depth_channel.is_some());
        loop {
            let have_colour = !with_colour || self.waiting.contains_key(&(index, false));
            let have_depth = !with_depth || self.waiting.contains_key(&(index, true));
            if have_colour && have_depth {
                return Ok((
                    self.waiting.remove(&(index, false)),
                    self.waiting.remove(&(index, true)),
                ));
            }
            let Some(message) = self.messages.next() else {
                return Err(PipelineError::Worker(format!(
                    "the bag ended before the messages of frame {index}"
                )));
            };
            let message = message?;
            let channel = message.channel.id;
            let (count, depth) = if Some(channel) == self.colour_channel {
                (&mut self.read.0, false)
            } else if Some(channel) == self.depth_channel {
                (&mut self.read.1, true)
            } else {
                continue;
            };
            let frame = *count;
            *count += 1;
            if self.wanted.contains(&frame) {
                self.waiting.insert((frame, depth), message.data);
            }
        }
    }
}
