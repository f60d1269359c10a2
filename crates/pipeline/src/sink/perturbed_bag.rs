//! A recorded bag's camera, perturbed, into its spool of the bag of the same topics
//! ([`rslam_core::dataset::ros2::PerturbedBag`]): each source frame's colour and depth are
//! unpacked, encoded as the recorded ones were and written on one worker thread, in source
//! order (a depth camera of its own writes only its depth).

use std::collections::HashMap;
use std::sync::Arc;

use rslam_core::dataset::ros2::PerturbedBag;
use rslam_core::ImagePool;
use rslam_gpu::MappedFrame;

use super::FrameSink;
use crate::encoder_pool::EncoderPool;
use crate::plan::{FramePlan, SourceOutputs};
use crate::PipelineError;

pub struct PerturbedBagSink<'a> {
    bag: Arc<PerturbedBag>,
    camera: usize,
    /// One thread keeps the messages in order; its queue of four frames holds the GPU back when
    /// the disk is slow.
    writer: EncoderPool,
    images: Arc<ImagePool>,
    plan: &'a FramePlan,
    /// Per source frame: its colour and depth capture times as recorded.
    recorded_times: &'a [(f64, f64)],
    outputs: HashMap<usize, SourceOutputs>,
}

impl<'a> PerturbedBagSink<'a> {
    /// Writes camera `camera`'s frames into `bag`.
    pub fn new(
        bag: Arc<PerturbedBag>,
        camera: usize,
        plan: &'a FramePlan,
        recorded_times: &'a [(f64, f64)],
    ) -> Self {
        Self {
            bag,
            camera,
            writer: EncoderPool::new(1, 4),
            images: Arc::default(),
            outputs: plan.outputs_by_source(),
            plan,
            recorded_times,
        }
    }

    /// Waits for the camera's frames to be in its spool.
    pub fn finish(self) -> Result<(), PipelineError> {
        self.writer.finish()
    }
}

impl FrameSink for PerturbedBagSink<'_> {
    fn accept(&mut self, source: usize, frame: MappedFrame) -> Result<(), PipelineError> {
        let Some(outputs) = self.outputs.get(&source) else {
            return Ok(());
        };
        let (rgb_time, depth_time) = self.recorded_times[source];
        let colour_shifts: Vec<f64> = match self.bag.has_colour(self.camera) {
            true => outputs
                .rgb
                .iter()
                .map(|&j| self.plan.frames[j].rgb_time - rgb_time)
                .collect(),
            false => Vec::new(),
        };
        // Several output frames share one depth capture under misalignment: it is one message.
        let mut depth_shifts: Vec<f64> = outputs
            .depth
            .iter()
            .map(|&j| self.plan.frames[j].depth_time - depth_time)
            .collect();
        depth_shifts.dedup();
        let (bag, images, camera) = (self.bag.clone(), self.images.clone(), self.camera);
        self.writer.submit(move || {
            let (colour, depth) = frame.unpack(&images)?;
            for &shift in &colour_shifts {
                bag.write_colour(camera, source, shift, &colour)?;
            }
            if let Some(depth) = &depth {
                for &shift in &depth_shifts {
                    bag.write_depth(camera, source, shift, depth)?;
                }
            }
            images.give_rgb(colour);
            if let Some(depth) = depth {
                images.give_depth(depth);
            }
            Ok(())
        })
    }
}
