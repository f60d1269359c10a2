//! A recorded bag's camera, perturbed, into a bag of the same topics
//! ([`rslam_core::dataset::ros2::PerturbedBag`]): each source frame's colour and depth are
//! unpacked, encoded as the recorded ones were and written on one worker thread, in source
//! order, between the messages copied from the input; `metadata.yaml`, the checksums and the
//! manifest come last.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use rslam_core::dataset::ros2::PerturbedBag;
use rslam_core::dataset::{ContentWriter, Manifest};
use rslam_core::ImagePool;
use rslam_gpu::MappedFrame;

use super::{seal_bag, FrameSink};
use crate::encoder_pool::EncoderPool;
use crate::plan::{FramePlan, SourceOutputs};
use crate::PipelineError;

pub struct PerturbedBagSink<'a> {
    bag: Arc<Mutex<PerturbedBag>>,
    /// One thread keeps the messages in order; its queue of four frames holds the GPU back when
    /// the disk is slow.
    writer: EncoderPool,
    content: ContentWriter,
    images: Arc<ImagePool>,
    plan: &'a FramePlan,
    /// Per source frame: its colour and depth capture times as recorded.
    recorded_times: &'a [(f64, f64)],
    outputs: HashMap<usize, SourceOutputs>,
}

impl<'a> PerturbedBagSink<'a> {
    pub fn new(
        bag: PerturbedBag,
        content: ContentWriter,
        plan: &'a FramePlan,
        recorded_times: &'a [(f64, f64)],
    ) -> Self {
        Self {
            bag: Arc::new(Mutex::new(bag)),
            writer: EncoderPool::new(1, 4),
            content,
            images: Arc::default(),
            outputs: plan.outputs_by_source(),
            plan,
            recorded_times,
        }
    }

    /// Copies the rest of the input, closes the bag, writes `metadata.yaml`, then the
    /// checksums and `manifest`, last.
    pub fn finish(self, manifest: Manifest) -> Result<Manifest, PipelineError> {
        self.writer.finish()?;
        let bag = Arc::try_unwrap(self.bag)
            .map_err(|_| PipelineError::Worker("the bag is still shared".into()))?
            .into_inner()
            .unwrap_or_else(|p| p.into_inner());
        seal_bag(self.content, bag.finish()?, manifest)
    }
}

impl FrameSink for PerturbedBagSink<'_> {
    fn accept(&mut self, source: usize, frame: MappedFrame) -> Result<(), PipelineError> {
        let Some(outputs) = self.outputs.get(&source) else {
            return Ok(());
        };
        let (rgb_time, depth_time) = self.recorded_times[source];
        let colour_shifts: Vec<f64> = outputs
            .rgb
            .iter()
            .map(|&j| self.plan.frames[j].rgb_time - rgb_time)
            .collect();
        // Several output frames share one depth capture under misalignment: it is one message.
        let mut depth_shifts: Vec<f64> = outputs
            .depth
            .iter()
            .map(|&j| self.plan.frames[j].depth_time - depth_time)
            .collect();
        depth_shifts.dedup();
        let (bag, images) = (self.bag.clone(), self.images.clone());
        self.writer.submit(move || {
            let (colour, depth) = frame.unpack(&images)?;
            let mut bag = bag.lock().unwrap_or_else(|p| p.into_inner());
            for &shift in &colour_shifts {
                bag.write_colour(source, shift, &colour)?;
            }
            if let Some(depth) = &depth {
                for &shift in &depth_shifts {
                    bag.write_depth(source, shift, depth)?;
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
