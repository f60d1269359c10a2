//! One RGB-D camera into a ROS 2 bag: each source frame's colour, depth and ground truth are
//! unpacked, converted and written as messages on one worker thread, in the order the frames
//! arrive (capture order, so the bag's log time follows the stamps), while the frame loop goes on;
//! `metadata.yaml`, the checksums and the manifest come last.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use rslam_core::dataset::ros2::{CameraBag, ClosedBag};
use rslam_core::dataset::{ContentWriter, Manifest};
use rslam_core::{ImagePool, Pose, Trajectory};
use rslam_gpu::MappedFrame;

use super::FrameSink;
use crate::encoder_pool::EncoderPool;
use crate::plan::{FramePlan, SourceOutputs};
use crate::PipelineError;

pub struct CameraBagSink<'a> {
    bag: Arc<Mutex<CameraBag>>,
    /// One thread keeps the messages in order; its queue of four frames holds the GPU back when
    /// the disk is slow.
    writer: EncoderPool,
    content: ContentWriter,
    images: Arc<ImagePool>,
    plan: &'a FramePlan,
    ground_truth: &'a Trajectory,
    outputs: HashMap<usize, SourceOutputs>,
}

impl<'a> CameraBagSink<'a> {
    /// Writes into `bag`; `content` seals the folder it lies in. `ground_truth` holds one pose
    /// per output frame of `plan`.
    pub fn new(
        bag: CameraBag,
        content: ContentWriter,
        plan: &'a FramePlan,
        ground_truth: &'a Trajectory,
    ) -> Self {
        Self {
            bag: Arc::new(Mutex::new(bag)),
            writer: EncoderPool::new(1, 4),
            content,
            images: Arc::default(),
            outputs: plan.outputs_by_source(),
            plan,
            ground_truth,
        }
    }

    /// Closes the bag, writes `metadata.yaml`, then the checksums and `manifest`, last.
    pub fn finish(self, manifest: Manifest) -> Result<Manifest, PipelineError> {
        self.writer.finish()?;
        let bag = Arc::try_unwrap(self.bag)
            .map_err(|_| PipelineError::Worker("the bag is still shared".into()))?
            .into_inner()
            .unwrap_or_else(|p| p.into_inner());
        seal_bag(self.content, bag.finish()?, manifest)
    }
}

/// Seals a bag's folder: the closed storage file's checksum and `metadata.yaml`, then the
/// checksums and `manifest`, last.
pub fn seal_bag(
    content: ContentWriter,
    closed: ClosedBag,
    manifest: Manifest,
) -> Result<Manifest, PipelineError> {
    content.record(&closed.file, closed.blake3);
    content.write("metadata.yaml", closed.metadata.as_bytes())?;
    Ok(content.finish(manifest)?)
}

impl FrameSink for CameraBagSink<'_> {
    fn accept(&mut self, source: usize, frame: MappedFrame) -> Result<(), PipelineError> {
        let Some(outputs) = self.outputs.get(&source) else {
            return Ok(());
        };
        let colours: Vec<(f64, Pose)> = outputs
            .rgb
            .iter()
            .map(|&j| (self.plan.frames[j].rgb_time, self.ground_truth.poses[j]))
            .collect();
        // Several output frames share one depth capture under misalignment: it is one message.
        let mut depth_times: Vec<f64> = outputs
            .depth
            .iter()
            .map(|&j| self.plan.frames[j].depth_time)
            .collect();
        depth_times.dedup();
        let (bag, images) = (self.bag.clone(), self.images.clone());
        self.writer.submit(move || {
            let (color, depth) = frame.unpack(&images)?;
            let mut bag = bag.lock().unwrap_or_else(|p| p.into_inner());
            for (time, pose) in &colours {
                bag.write_rgb(*time, &color)?;
                bag.write_ground_truth(*time, pose)?;
            }
            if let Some(depth) = &depth {
                for &time in &depth_times {
                    bag.write_depth(time, depth)?;
                }
            }
            images.give_rgb(color);
            if let Some(depth) = depth {
                images.give_depth(depth);
            }
            Ok(())
        })
    }
}
