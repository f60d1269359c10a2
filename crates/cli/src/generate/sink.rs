//! Where read-back frames go: each source frame's colour and depth are encoded on the worker
//! threads into every output frame that uses them, and the manifest is written last.

use std::sync::Arc;

use anyhow::Context;
use rslam_core::dataset::{DatasetWriter, Manifest, OutputFrame};
use rslam_core::{DepthImage, RgbImage, Trajectory};

use super::encoder_pool::EncoderPool;

/// Which source frame each output frame's colour and depth come from, and their capture times.
pub struct OutputPlan {
    pub rgb_source: Vec<usize>,
    pub depth_source: Vec<usize>,
    pub frames: Vec<OutputFrame>,
}

impl OutputPlan {
    /// Output frame `j` is captured at `rgb_time(j)`; its depth was captured when the output
    /// frame showing the depth's source was, plus that source's own depth–colour offset.
    pub fn new(
        rgb_source: Vec<usize>,
        depth_source: Vec<usize>,
        rgb_time: impl Fn(usize) -> f64,
        depth_offset: impl Fn(usize) -> f64,
    ) -> Self {
        let time_of_source: std::collections::HashMap<usize, f64> = rgb_source
            .iter()
            .enumerate()
            .map(|(j, &s)| (s, rgb_time(j)))
            .collect();
        let frames = (0..rgb_source.len())
            .map(|j| {
                let d = depth_source[j];
                OutputFrame {
                    rgb_time: rgb_time(j),
                    depth_time: time_of_source
                        .get(&d)
                        .copied()
                        .unwrap_or_else(|| rgb_time(j))
                        + depth_offset(d),
                }
            })
            .collect();
        Self {
            rgb_source,
            depth_source,
            frames,
        }
    }

    /// The ground truth of the output: the pose of each output frame's colour source, stamped
    /// with its capture time. `poses` holds one pose per source frame.
    pub fn ground_truth(&self, poses: &[rslam_core::Pose]) -> Trajectory {
        Trajectory::new(
            self.frames.iter().map(|f| f.rgb_time).collect(),
            self.rgb_source.iter().map(|&s| poses[s]).collect(),
        )
    }

    /// Every source frame some output needs, ascending.
    pub fn needed_sources(&self) -> Vec<usize> {
        let mut all: Vec<usize> = self
            .rgb_source
            .iter()
            .chain(&self.depth_source)
            .copied()
            .collect();
        all.sort_unstable();
        all.dedup();
        all
    }
}

pub struct FrameSink {
    writer: Arc<DatasetWriter>,
    pool: EncoderPool,
    plan: OutputPlan,
}

impl FrameSink {
    pub fn new(writer: DatasetWriter, plan: OutputPlan) -> Self {
        let threads = std::thread::available_parallelism().map_or(2, |n| n.get());
        Self {
            writer: Arc::new(writer),
            pool: EncoderPool::new(threads, 2 * threads),
            plan,
        }
    }

    pub fn plan(&self) -> &OutputPlan {
        &self.plan
    }

    pub fn intrinsics(&self) -> rslam_core::Intrinsics {
        self.writer.intrinsics()
    }

    /// Queues the writes of source frame `source`; `depth` is `None` for image-only inputs.
    pub fn accept(
        &self,
        source: usize,
        color: RgbImage,
        depth: Option<DepthImage>,
    ) -> anyhow::Result<()> {
        let color = Arc::new(color);
        for (j, _) in self
            .plan
            .rgb_source
            .iter()
            .enumerate()
            .filter(|(_, &s)| s == source)
        {
            let (writer, color, time) = (
                self.writer.clone(),
                color.clone(),
                self.plan.frames[j].rgb_time,
            );
            self.pool
                .submit(move || Ok(writer.write_rgb(j, time, &color)?))?;
        }
        let outputs: Vec<usize> = (0..self.plan.depth_source.len())
            .filter(|&j| self.plan.depth_source[j] == source)
            .collect();
        if let (Some(depth), Some(&first)) = (depth, outputs.first()) {
            let (writer, time) = (self.writer.clone(), self.plan.frames[first].depth_time);
            self.pool
                .submit(move || Ok(writer.write_depth(&outputs, time, &depth)?))?;
        }
        Ok(())
    }

    /// Waits for the encoders, then writes trajectory, index files and the manifest.
    pub fn finish(self, ground_truth: &Trajectory, manifest: &Manifest) -> anyhow::Result<()> {
        self.pool.finish()?;
        let writer = Arc::try_unwrap(self.writer)
            .map_err(|_| anyhow::anyhow!("dataset writer still shared after encoding"))?;
        let root = writer.root().to_path_buf();
        writer
            .finish(&self.plan.frames, ground_truth, manifest)
            .with_context(|| format!("finishing dataset {}", root.display()))
    }
}
