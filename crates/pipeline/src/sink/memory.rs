//! Output frames in memory: source frames are held until every output frame that needs them has
//! been assembled, then each output frame goes to a callback, in order.

use std::collections::HashMap;
use std::ops::Range;

use rslam_core::{DepthImage, ImagePool, MaskImage, RgbImage};
use rslam_gpu::MappedFrame;

use super::FrameSink;
use crate::plan::FramePlan;
use crate::PipelineError;

/// One output frame: what a SLAM system would read as frame `index`.
#[derive(Clone, Debug, PartialEq)]
pub struct RgbdFrame {
    pub index: usize,
    pub rgb_time: f64,
    pub depth_time: f64,
    pub color: RgbImage,
    /// `None` for inputs without depth.
    pub depth: Option<DepthImage>,
    /// The instance mask at the colour's instant; `None` without actors.
    pub mask: Option<MaskImage>,
}

pub struct MemorySink<'a, F> {
    plan: &'a FramePlan,
    outputs: Range<usize>,
    next: usize,
    colors: HashMap<usize, RgbImage>,
    depths: HashMap<usize, DepthImage>,
    masks: HashMap<usize, MaskImage>,
    with_depth: bool,
    deliver: F,
}

impl<'a, F: FnMut(RgbdFrame) -> Result<(), PipelineError>> MemorySink<'a, F> {
    /// Hands output frames `outputs` of `plan` to `deliver`.
    pub fn new(plan: &'a FramePlan, outputs: Range<usize>, with_depth: bool, deliver: F) -> Self {
        Self {
            plan,
            next: outputs.start,
            outputs,
            colors: HashMap::new(),
            depths: HashMap::new(),
            masks: HashMap::new(),
            with_depth,
            deliver,
        }
    }

    fn last_use(&self, sources: &[usize], source: usize) -> Option<usize> {
        self.outputs.clone().rev().find(|&j| sources[j] == source)
    }

    fn emit_ready(&mut self) -> Result<(), PipelineError> {
        while self.next < self.outputs.end {
            let j = self.next;
            let (rgb, depth) = (
                self.plan.rgb_source[j],
                self.plan.depth_source.get(j).copied(),
            );
            let depth_ready =
                !self.with_depth || depth.is_some_and(|d| self.depths.contains_key(&d));
            if !self.colors.contains_key(&rgb) || !depth_ready {
                return Ok(());
            }
            let last = self.last_use(&self.plan.rgb_source, rgb) == Some(j);
            let color = take(&mut self.colors, rgb, last)
                .ok_or_else(|| PipelineError::Worker(format!("colour of frame {rgb} lost")))?;
            let mask = take(&mut self.masks, rgb, last);
            let depth = match depth.filter(|_| self.with_depth) {
                Some(d) => {
                    let last = self.last_use(&self.plan.depth_source, d) == Some(j);
                    take(&mut self.depths, d, last)
                }
                None => None,
            };
            let times = self.plan.frames.get(j).copied();
            (self.deliver)(RgbdFrame {
                index: j,
                rgb_time: times.map_or(0.0, |t| t.rgb_time),
                depth_time: times.map_or(0.0, |t| t.depth_time),
                color,
                depth,
                mask,
            })?;
            self.next += 1;
        }
        Ok(())
    }
}

/// The entry for `key`: moved out at its last use, cloned before.
fn take<T: Clone>(map: &mut HashMap<usize, T>, key: usize, last_use: bool) -> Option<T> {
    if last_use {
        map.remove(&key)
    } else {
        map.get(&key).cloned()
    }
}

impl<F: FnMut(RgbdFrame) -> Result<(), PipelineError>> FrameSink for MemorySink<'_, F> {
    fn wants_mask(&self) -> bool {
        true
    }

    /// Unpacks on the frame loop's thread: the frames leave through the callback there.
    fn accept(&mut self, source: usize, mut frame: MappedFrame) -> Result<(), PipelineError> {
        let mask = frame.mask.take().map(|m| m.unpack()).transpose()?;
        let (color, depth) = frame.unpack(&ImagePool::default())?;
        let outputs = self.outputs.clone();
        if outputs.clone().any(|j| self.plan.rgb_source[j] == source) {
            self.colors.insert(source, color);
            if let Some(mask) = mask {
                self.masks.insert(source, mask);
            }
        }
        if let Some(depth) = depth.filter(|_| self.with_depth) {
            if outputs.clone().any(|j| self.plan.depth_source[j] == source) {
                self.depths.insert(source, depth);
            }
        }
        self.emit_ready()
    }
}
