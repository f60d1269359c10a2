//! A dataset on disk: each source frame's colour, depth and instance mask are encoded on worker
//! threads into every output frame that uses them; index files, the state log of stateful perturbations
//! (`sensor_state.csv`), checksums and the manifest come last.

use std::collections::HashMap;
use std::sync::Arc;

use rslam_core::dataset::{DatasetWriter, Manifest};
use rslam_core::{ImagePool, Trajectory};
use rslam_gpu::MappedFrame;

use super::FrameSink;
use crate::encoder_pool::EncoderPool;
use crate::plan::{FramePlan, SourceOutputs};
use crate::state_log::StateTable;
use crate::PipelineError;

/// The per-frame state of stateful perturbations (auto_exposure's exposure and gain).
pub const STATE_FILE: &str = "sensor_state.csv";

pub struct DatasetSink<'a> {
    writer: Arc<DatasetWriter>,
    pool: EncoderPool,
    /// Images handed back once every file made from them is written.
    images: Arc<ImagePool>,
    plan: &'a FramePlan,
    outputs: HashMap<usize, SourceOutputs>,
    state: Option<StateTable>,
}

impl<'a> DatasetSink<'a> {
    pub fn new(writer: DatasetWriter, plan: &'a FramePlan) -> Self {
        Self {
            writer: Arc::new(writer),
            pool: EncoderPool::per_core(),
            images: Arc::default(),
            outputs: plan.outputs_by_source(),
            plan,
            state: None,
        }
    }

    /// Whether every file source frame `source` contributes to is on disk, complete (files
    /// appear under their final name only once whole).
    pub fn is_written(&self, source: usize) -> bool {
        let Some(outputs) = self.outputs.get(&source) else {
            return true;
        };
        let names = |j: usize| self.writer.frame_files(j, &self.plan.frames[j]);
        let root = self.writer.root();
        let rgb = outputs.rgb.iter().map(|&j| names(j).rgb);
        let depth = outputs.depth.iter().map(|&j| names(j).depth);
        let masks = (outputs.rgb.iter())
            .filter(|_| self.writer.has_masks())
            .map(|&j| self.writer.mask_file(j, &self.plan.frames[j]));
        (rgb.chain(depth).chain(masks)).all(|name| root.join(name).is_file())
    }

    /// Waits for the encoders, then writes `sensor_files` (relative path, text), trajectory,
    /// index files, checksums and the manifest.
    pub fn finish(
        self,
        ground_truth: &Trajectory,
        sensor_files: &[(String, String)],
        manifest: Manifest,
    ) -> Result<Manifest, PipelineError> {
        self.pool.finish()?;
        let writer = Arc::try_unwrap(self.writer)
            .map_err(|_| PipelineError::Worker("dataset writer still shared".into()))?;
        if let Some(table) = &self.state {
            writer.write_text(STATE_FILE, &state_csv(table, self.plan))?;
        }
        for (relative, text) in sensor_files {
            writer.write_text(relative, text)?;
        }
        Ok(writer.finish(&self.plan.frames, ground_truth, manifest)?)
    }
}

/// One row per output frame: its index, its colour timestamp, and the state its colour source
/// frame was made with (empty cells where an item did not run on it).
fn state_csv(table: &StateTable, plan: &FramePlan) -> String {
    let mut csv = format!("frame,timestamp,{}\n", table.columns.join(","));
    for (j, frame) in plan.frames.iter().enumerate() {
        let cells: Vec<String> = match table.rows.get(&plan.rgb_source[j]) {
            Some(row) => row
                .iter()
                .map(|cell| cell.map(|v| v.to_string()).unwrap_or_default())
                .collect(),
            None => vec![String::new(); table.columns.len()],
        };
        csv.push_str(&format!("{j},{:.6},{}\n", frame.rgb_time, cells.join(",")));
    }
    csv
}

impl FrameSink for DatasetSink<'_> {
    fn wants_mask(&self) -> bool {
        self.writer.has_masks()
    }

    fn accept_state(&mut self, table: StateTable) -> Result<(), PipelineError> {
        self.state = Some(table);
        Ok(())
    }

    /// Colour, depth and mask are unpacked on the encoder threads, each in the job that encodes
    /// it (a source frame repeated in several output frames is encoded into each by that one
    /// job). A mask goes with the colour: it is of the colour's instant.
    fn accept(&mut self, source: usize, frame: MappedFrame) -> Result<(), PipelineError> {
        let Some(outputs) = self.outputs.get(&source) else {
            return Ok(());
        };
        let with_times = |outputs: &[usize]| -> Vec<_> {
            outputs.iter().map(|&j| (j, self.plan.frames[j])).collect()
        };
        let (rgb_outputs, depth_outputs) = (with_times(&outputs.rgb), with_times(&outputs.depth));
        if let (Some(mask), false) = (frame.mask, rgb_outputs.is_empty()) {
            let (writer, outputs) = (self.writer.clone(), rgb_outputs.clone());
            self.pool.submit(move || {
                let mask = mask.unpack()?;
                for (j, times) in &outputs {
                    writer.write_mask(*j, times, &mask)?;
                }
                Ok(())
            })?;
        }
        if !rgb_outputs.is_empty() {
            let (writer, images, color) = (self.writer.clone(), self.images.clone(), frame.color);
            self.pool.submit(move || {
                let color = color.unpack(&images)?;
                for (j, times) in &rgb_outputs {
                    writer.write_rgb(*j, times, &color)?;
                }
                images.give_rgb(color);
                Ok(())
            })?;
        }
        if let (Some(depth), false) = (frame.depth, depth_outputs.is_empty()) {
            let (writer, images) = (self.writer.clone(), self.images.clone());
            self.pool.submit(move || {
                let depth = depth.unpack(&images)?;
                writer.write_depth(&depth_outputs, &depth)?;
                images.give_depth(depth);
                Ok(())
            })?;
        }
        Ok(())
    }
}
