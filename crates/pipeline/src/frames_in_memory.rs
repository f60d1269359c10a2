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
    spec: PerturbSpec,
    seed: u64,
}

impl FramesInMemory<SceneSource> {
    /// A scene along its path (see [`SceneJob`]).
    pub fn scene(ctx: &GpuContext, job: &SceneJob) -> Result<Self, PipelineError> {
        Self::resolved(ctx, job, job.resolve()?)
    }

    /// A scene along `poses` (camera-to-world) instead of the job's path
    /// ([`SceneJob::resolve_along`]).
    pub fn scene_along(
        ctx: &GpuContext,
        job: &SceneJob,
        poses: Vec<rslam_core::Pose>,
    ) -> Result<Self, PipelineError> {
        Self::resolved(ctx, job, job.resolve_along(poses)?)
    }

    fn resolved(
        ctx: &GpuContext,
        job: &SceneJob,
        resolved: crate::scene_job::ResolvedScene,
    ) -> Result<Self, PipelineError> {
        let source = SceneSource::new(ctx, &resolved.scene, job.camera, resolved.poses)?;
        Ok(Self {
            pipeline: Pipeline::new(ctx, source, &job.spec, job.seed)?,
            plan: resolved.plan,
            spec: job.spec.clone(),
            seed: job.seed,
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
            spec: spec.clone(),
            seed,
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
        check_depth(spec, &source)?;
        check_frame_items_only(spec)?;
        let plan = FramePlan::images_at(source.frame_numbers(), source.has_depth(), spec, seed);
        Ok(Self {
            pipeline: Pipeline::new(ctx, source, spec, seed)?,
            plan,
            spec: spec.clone(),
            seed,
        })
    }

    /// Other frames of the same size through the same perturbations: the GPU pipelines built by
    /// [`FramesInMemory::buffers`] are kept, the plan is made anew for the new frame numbers.
    pub fn set_frames(&mut self, source: BufferSource) -> Result<(), PipelineError> {
        let (width, height) = self.pipeline.source().size();
        if source.size() != (width, height) {
            let (w, h) = source.size();
            return Err(PipelineError::option(
                "frames",
                format!("{w}x{h} frames given to perturbations built for {width}x{height}"),
            ));
        }
        check_depth(&self.spec, &source)?;
        self.plan = FramePlan::images_at(
            source.frame_numbers(),
            source.has_depth(),
            &self.spec,
            self.seed,
        );
        self.pipeline.set_source(source);
        Ok(())
    }
}

impl<S: FrameSource> FramesInMemory<S> {
    pub fn plan(&self) -> &FramePlan {
        &self.plan
    }

    /// Width and height of every frame.
    pub fn frame_size(&self) -> (u32, u32) {
        self.pipeline.source().size()
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

fn check_depth(spec: &PerturbSpec, source: &BufferSource) -> Result<(), PipelineError> {
    if !spec.depth.is_empty() && !source.has_depth() {
        return Err(PipelineError::option(
            "--perturb",
            format!("'{spec}': depth corruptions need depth, and the frames have none"),
        ));
    }
    Ok(())
}
