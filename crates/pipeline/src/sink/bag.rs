//! One RGB-D camera into a ROS 2 bag: each source frame's colour, depth and ground truth become
//! messages as the frame arrives (source frames come in capture order, so the bag's log time
//! follows the stamps); `metadata.yaml`, the checksums and the manifest come last.

use std::collections::HashMap;

use rslam_core::dataset::ros2::CameraBag;
use rslam_core::dataset::{ContentWriter, Manifest};
use rslam_core::{ImagePool, Trajectory};
use rslam_gpu::MappedFrame;

use super::FrameSink;
use crate::plan::{FramePlan, SourceOutputs};
use crate::PipelineError;

pub struct CameraBagSink<'a> {
    bag: CameraBag,
    content: ContentWriter,
    images: ImagePool,
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
            bag,
            content,
            images: ImagePool::default(),
            outputs: plan.outputs_by_source(),
            plan,
            ground_truth,
        }
    }

    /// Closes the bag, writes `metadata.yaml`, then the checksums and `manifest`, last.
    pub fn finish(self, manifest: Manifest) -> Result<Manifest, PipelineError> {
        let (_, metadata) = self.bag.finish()?;
        self.content.write("metadata.yaml", metadata.as_bytes())?;
        Ok(self.content.finish(manifest)?)
    }
}

impl FrameSink for CameraBagSink<'_> {
    fn accept(&mut self, source: usize, frame: MappedFrame) -> Result<(), PipelineError> {
        let Some(outputs) = self.outputs.get(&source) else {
            return Ok(());
        };
        let (color, depth) = frame.unpack(&self.images)?;
        for &j in &outputs.rgb {
            let time = self.plan.frames[j].rgb_time;
            self.bag.write_rgb(time, &color)?;
            self.bag
                .write_ground_truth(time, &self.ground_truth.poses[j])?;
        }
        // Several output frames share one depth capture under misalignment: it is one message.
        let mut depth_times: Vec<f64> = outputs
            .depth
            .iter()
            .map(|&j| self.plan.frames[j].depth_time)
            .collect();
        depth_times.dedup();
        if let Some(depth) = &depth {
            for time in depth_times {
                self.bag.write_depth(time, depth)?;
            }
        }
        self.images.give_rgb(color);
        if let Some(depth) = depth {
            self.images.give_depth(depth);
        }
        Ok(())
    }
}
