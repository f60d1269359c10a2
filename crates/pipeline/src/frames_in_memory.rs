//! Frames in memory, for the viewer and the Python package: a source, its perturbations and its
//! plan on the caller's GPU context; output frames come back as buffers and nothing is written.

use std::ops::Range;

use rslam_core::dataset::SourceDataset;
use rslam_gpu::GpuContext;
use rslam_perturb::PerturbSpec;

use crate::perturb_dataset::{check_dataset_spec, dataset_plan};
use crate::perturb_images::check_frame_items_only;
use crate::pipeline::Pipeline;
use crate::plan::FramePlan;
use crate::progress::Silent;
use crate::scene_job::SceneJob;
use crate::sink::{MemorySink, RgbdFrame};
use crate::source::{BufferSource, DatasetSource, FrameSource, SceneSource};
use crate::PipelineError;

pub struct FramesInMemory<S> {
    pipeline: Pipeline<S>,
    plan: FramePlan,
}

impl FramesInMemory<SceneSource> {
    /// A scene along its path (see [`SceneJob`]).
    pub fn scene(ctx: &GpuContext, job: &SceneJob) -> Result<Self, PipelineError> {
        let resolved = job.resolve()?;
        let source = SceneSource::new(ctx, &resolved.scene, job.camera, resolved.poses)?;
        Ok(Self {
            pipeline: Pipeline::new(ctx, source, &job.spec, job.seed)?,
            plan: resolved.plan,
        })
    }
}

impl FramesInMemory<DatasetSource> {
    /// A dataset on disk, read with `rslam_core::dataset::read_dataset`.
    pub fn dataset(
        ctx: &GpuContext,
        dataset: &SourceDataset,
        spec: &PerturbSpec,
        seed: u64,
    ) -> Result<Self, PipelineError> {
        check_dataset_spec(dataset, spec)?;
        Ok(Self {
            pipeline: Pipeline::new(ctx, DatasetSource::new(dataset), spec, seed)?,
            plan: dataset_plan(dataset, spec, seed),
        })
    }
}

impl FramesInMemory<BufferSource> {
    /// Frames given as buffers; frame i is the RNG's frame i. Image and depth corruptions only.
    pub fn buffers(
        ctx: &GpuContext,
        source: BufferSource,
        spec: &PerturbSpec,
        seed: u64,
    ) -> Result<Self, PipelineError> {
        if !spec.depth.is_empty() && !source.has_depth() {
            return Err(PipelineError::option(
                "--perturb",
                format!("'{spec}': depth corruptions need depth, and the frames have none"),
            ));
        }
        check_frame_items_only(spec)?;
        let plan = FramePlan::images(source.len(), source.has_depth(), spec, seed);
        Ok(Self {
            pipeline: Pipeline::new(ctx, source, spec, seed)?,
            plan,
        })
    }
}

impl<S: FrameSource> FramesInMemory<S> {
    pub fn plan(&self) -> &FramePlan {
        &self.plan
    }

    /// Output frames `outputs`, in order, to `deliver`; the GPU keeps several frames in flight.
    pub fn frames(
        &mut self,
        ctx: &GpuContext,
        outputs: Range<usize>,
        deliver: impl FnMut(RgbdFrame) -> Result<(), PipelineError>,
    ) -> Result<(), PipelineError> {
        if outputs.end > self.plan.len() || outputs.start > outputs.end {
            return Err(PipelineError::option(
                "frames",
                format!(
                    "{}..{} is not within the {} output frames",
                    outputs.start,
                    outputs.end,
                    self.plan.len()
                ),
            ));
        }
        let with_depth = self.pipeline.source().has_depth();
        let sources = self.plan.sources_for(outputs.clone(), with_depth);
        let mut sink = MemorySink::new(&self.plan, outputs, with_depth, deliver);
        self.pipeline.run(ctx, &sources, &Silent, &mut sink)
    }

    /// Output frame `index`.
    pub fn frame(&mut self, ctx: &GpuContext, index: usize) -> Result<RgbdFrame, PipelineError> {
        let mut got = None;
        self.frames(ctx, index..index + 1, |frame| {
            got = Some(frame);
            Ok(())
        })?;
        got.ok_or_else(|| PipelineError::Worker(format!("frame {index} was not delivered")))
    }
}
