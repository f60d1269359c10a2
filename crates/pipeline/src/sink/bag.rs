//! One RGB-D camera into a ROS 2 bag: each source frame's colour, depth, ground truth and (with
//! actors) instance mask are
//! unpacked, converted and written as messages on one worker thread, in the order the frames
//! arrive (capture order, so the bag's log time follows the stamps), while the frame loop goes on;
//! `metadata.yaml`, the checksums and the manifest come last.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use rslam_core::dataset::ros2::{CameraBag, ClosedBag};
use rslam_core::dataset::{rounded_dynamic_fraction, ContentWriter, Manifest, MASK_IDS};
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
    /// Each output frame's dynamic fraction, with masks.
    fractions: Arc<Mutex<Vec<f64>>>,
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
            fractions: Arc::new(Mutex::new(vec![0.0; plan.len()])),
            plan,
            ground_truth,
        }
    }

    /// Closes the bag, writes `metadata.yaml`, then the checksums and `manifest` (with the
    /// frames' dynamic fractions, with masks), last.
    pub fn finish(self, mut manifest: Manifest) -> Result<Manifest, PipelineError> {
        self.writer.finish()?;
        let bag = Arc::try_unwrap(self.bag)
            .map_err(|_| PipelineError::Worker("the bag is still shared".into()))?
            .into_inner()
            .unwrap_or_else(|p| p.into_inner());
        if bag.has_masks() {
            let fractions = self.fractions.lock().unwrap_or_else(|p| p.into_inner());
            manifest.extra["masks"] = serde_json::json!({
                "ids": MASK_IDS,
                "dynamic_fraction": *fractions,
            });
        }
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
    fn wants_mask(&self) -> bool {
        self.bag
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .has_masks()
    }

    fn accept(&mut self, source: usize, frame: MappedFrame) -> Result<(), PipelineError> {
        let Some(outputs) = self.outputs.get(&source) else {
            return Ok(());
        };
        let colours: Vec<(usize, f64, Pose)> = (outputs.rgb.iter())
            .map(|&j| (j, self.plan.frames[j].rgb_time, self.ground_truth.poses[j]))
            .collect();
        // Several output frames share one depth capture under misalignment: it is one message.
        let mut depth_times: Vec<f64> = outputs
            .depth
            .iter()
            .map(|&j| self.plan.frames[j].depth_time)
            .collect();
        depth_times.dedup();
        let (bag, images) = (self.bag.clone(), self.images.clone());
        let fractions = self.fractions.clone();
        self.writer.submit(move || {
            let mut frame = frame;
            let mask = frame.mask.take().map(|m| m.unpack()).transpose()?;
            let (color, depth) = frame.unpack(&images)?;
            let mut bag = bag.lock().unwrap_or_else(|p| p.into_inner());
            for &(j, time, ref pose) in &colours {
                bag.write_rgb(time, &color)?;
                if let Some(mask) = &mask {
                    bag.write_mask(time, mask)?;
                    let mut fractions = fractions.lock().unwrap_or_else(|p| p.into_inner());
                    fractions[j] = rounded_dynamic_fraction(mask.dynamic_fraction());
                }
                bag.write_ground_truth(time, pose)?;
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
