//! A dataset on disk: each source frame's colour and depth are encoded on worker threads into
//! every output frame that uses them; index files, checksums and the manifest come last.

use std::sync::Arc;

use rslam_core::dataset::{DatasetWriter, Manifest};
use rslam_core::{DepthImage, RgbImage, Trajectory};

use super::FrameSink;
use crate::encoder_pool::EncoderPool;
use crate::plan::FramePlan;
use crate::PipelineError;

pub struct DatasetSink<'a> {
    writer: Arc<DatasetWriter>,
    pool: EncoderPool,
    plan: &'a FramePlan,
}

impl<'a> DatasetSink<'a> {
    pub fn new(writer: DatasetWriter, plan: &'a FramePlan) -> Self {
        Self {
            writer: Arc::new(writer),
            pool: EncoderPool::per_core(),
            plan,
        }
    }

    /// Whether every file source frame `source` contributes to is on disk, complete (files
    /// appear under their final name only once whole).
    pub fn is_written(&self, source: usize) -> bool {
        let root = self.writer.root();
        let files = |outputs: Vec<usize>, depth: bool| {
            outputs.into_iter().map(move |j| {
                let names = self.writer.frame_files(j, &self.plan.frames[j]);
                if depth {
                    names.depth
                } else {
                    names.rgb
                }
            })
        };
        files(self.plan.rgb_outputs(source), false)
            .chain(files(self.plan.depth_outputs(source), true))
            .all(|name| root.join(name).is_file())
    }

    /// Waits for the encoders, then writes trajectory, index files, checksums and the manifest.
    pub fn finish(
        self,
        ground_truth: &Trajectory,
        manifest: Manifest,
    ) -> Result<Manifest, PipelineError> {
        self.pool.finish()?;
        let writer = Arc::try_unwrap(self.writer)
            .map_err(|_| PipelineError::Worker("dataset writer still shared".into()))?;
        Ok(writer.finish(&self.plan.frames, ground_truth, manifest)?)
    }
}

impl FrameSink for DatasetSink<'_> {
    fn accept(
        &mut self,
        source: usize,
        color: RgbImage,
        depth: Option<DepthImage>,
    ) -> Result<(), PipelineError> {
        let color = Arc::new(color);
        for j in self.plan.rgb_outputs(source) {
            let (writer, color, frame) = (self.writer.clone(), color.clone(), self.plan.frames[j]);
            self.pool
                .submit(move || Ok(writer.write_rgb(j, &frame, &color)?))?;
        }
        let outputs: Vec<_> = self
            .plan
            .depth_outputs(source)
            .into_iter()
            .map(|j| (j, self.plan.frames[j]))
            .collect();
        if let (Some(depth), false) = (depth, outputs.is_empty()) {
            let writer = self.writer.clone();
            self.pool
                .submit(move || Ok(writer.write_depth(&outputs, &depth)?))?;
        }
        Ok(())
    }
}
