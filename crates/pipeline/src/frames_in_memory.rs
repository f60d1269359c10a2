//! Frames in memory, for the viewer and the Python package: a source, its perturbations and its
//! plan on the caller's GPU context; output frames come back as buffers and nothing is written,
//! or stay on the GPU in a [`ShownFrame`] for display. The spec can change between frames.

use std::ops::Range;

use rslam_core::dataset::SourceDataset;
use rslam_core::{Pose, Trajectory};
use rslam_gpu::GpuContext;
use rslam_perturb::PerturbSpec;

use crate::depth_colormap::DepthRange;
use crate::perturb_dataset::{dataset_plan, output_ground_truth};
use crate::pipeline::Pipeline;
use crate::plan::FramePlan;
use crate::progress::Silent;
use crate::scene_job::ActorFiles;
use crate::scene_job::SceneJob;
use crate::shown_frame::{Held, ShownFrame, ShownSources};
use crate::sink::{MemorySink, RgbdFrame};
use crate::source::{BufferSource, FrameSource, RecordedSource, SceneSource};
use crate::{scene_actors, settings, JobPart, PipelineError};

pub struct FramesInMemory<S> {
    pipeline: Pipeline<S>,
    plan: FramePlan,
    spec: PerturbSpec,
    seed: u64,
    /// What a new spec needs to make its plan.
    origin: Origin,
    /// Counts changes of the source frames themselves (a new deviation of the path).
    generation: u64,
}

enum Origin {
    Scene {
        clean: Trajectory,
        rate_hz: f64,
        /// The job's own actors, planned again with the walkers when the path or spec changes.
        actor_files: Vec<ActorFiles>,
    },
    Dataset(Box<SourceDataset>),
    Buffers,
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
        settings::check(
            &job.spec,
            &settings::one_camera_render("a one-camera scene"),
        )?;
        let mut source = SceneSource::new(
            ctx,
            &resolved.scene,
            job.camera,
            resolved.poses,
            job.capture.settings,
            resolved.actors,
        )?;
        source.set_sensor(ctx, &job.spec, job.rate_hz, job.seed)?;
        Ok(Self {
            pipeline: Pipeline::new(ctx, source, &job.spec, job.seed)?,
            plan: resolved.plan,
            spec: job.spec.clone(),
            seed: job.seed,
            origin: Origin::Scene {
                clean: resolved.clean,
                rate_hz: job.rate_hz,
                actor_files: job.actor_files.clone(),
            },
            generation: 0,
        })
    }

    /// The poses of the output frames with their times: the ground truth a render writes.
    pub fn ground_truth(&self) -> Trajectory {
        self.plan.ground_truth(self.pipeline.source().poses())
    }

    /// Another spec and seed; trajectory items deviate the path anew.
    pub fn set_spec(
        &mut self,
        ctx: &GpuContext,
        spec: &PerturbSpec,
        seed: u64,
    ) -> Result<(), PipelineError> {
        let Origin::Scene {
            clean,
            rate_hz,
            actor_files,
        } = &self.origin
        else {
            return Err(PipelineError::Worker(
                "scene frames without their path".into(),
            ));
        };
        settings::check(spec, &settings::one_camera_render("a one-camera scene"))?;
        let deviated = rslam_perturb::trajectory::deviate(clean, spec, seed);
        let plan = FramePlan::rendered(deviated.len(), *rate_hz, spec, seed);
        let rate_hz = *rate_hz;
        let path_changed = deviated.poses != self.pipeline.source().poses();
        let with_walkers = !(spec.world.is_empty() && self.spec.world.is_empty());
        let walkers_changed = with_walkers && (spec.world != self.spec.world || seed != self.seed);
        let has_actors = !spec.world.is_empty() || !actor_files.is_empty();
        if walkers_changed || (path_changed && has_actors) {
            let scene = self.pipeline.source().scene().clone();
            let files = actor_files.as_slice();
            let actors = scene_actors::plan(&scene, (spec, files), seed, &deviated.poses, rate_hz)?;
            self.pipeline.source_mut().set_actors(ctx, actors)?;
        }
        let shutter_changed = self
            .pipeline
            .source_mut()
            .set_sensor(ctx, spec, rate_hz, seed)?;
        if path_changed || shutter_changed || walkers_changed {
            self.pipeline.source_mut().set_poses(deviated.poses);
            self.generation += 1;
        }
        self.take_spec(ctx, spec, seed, plan)
    }

    /// The view from `world_from_camera` (a free camera) in `shown`, perturbed as output frame
    /// `index` would be.
    pub fn show_from(
        &mut self,
        ctx: &GpuContext,
        world_from_camera: &Pose,
        index: usize,
        shown: &mut ShownFrame,
        range: DepthRange,
    ) -> Result<(), PipelineError> {
        let source = self.output_sources(index)?.rgb;
        let held = Held {
            sources: ShownSources {
                rgb: source,
                depth: source,
            },
            pose: Some(*world_from_camera),
            generation: self.generation,
        };
        self.pipeline
            .show_with(ctx, held, shown, range, |scene, encoder, frame, _| {
                scene.record_from(ctx, encoder, frame, world_from_camera)
            })
    }
}

impl FramesInMemory<RecordedSource> {
    /// A dataset on disk, read with `rslam_core::dataset::read_dataset`.
    pub fn dataset(
        ctx: &GpuContext,
        dataset: &SourceDataset,
        spec: &PerturbSpec,
        seed: u64,
    ) -> Result<Self, PipelineError> {
        settings::check(
            spec,
            &settings::recorded_dataset(dataset, &dataset.root, false),
        )?;
        Ok(Self {
            pipeline: Pipeline::new(ctx, RecordedSource::dataset(dataset), spec, seed)?,
            plan: dataset_plan(dataset, spec, seed),
            spec: spec.clone(),
            seed,
            origin: Origin::Dataset(Box::new(dataset.clone())),
            generation: 0,
        })
    }

    /// The ground truth a perturbed copy of the dataset would carry (empty without one).
    pub fn ground_truth(&self) -> Trajectory {
        match &self.origin {
            Origin::Dataset(dataset) => {
                output_ground_truth(dataset, &self.plan, crate::plan::restamps(&self.spec))
            }
            _ => Trajectory::default(),
        }
    }

    /// Another spec and seed; trajectory items are refused (recorded frames cannot move).
    pub fn set_spec(
        &mut self,
        ctx: &GpuContext,
        spec: &PerturbSpec,
        seed: u64,
    ) -> Result<(), PipelineError> {
        let Origin::Dataset(dataset) = &self.origin else {
            return Err(PipelineError::Worker(
                "dataset frames without their dataset".into(),
            ));
        };
        settings::check(
            spec,
            &settings::recorded_dataset(dataset, &dataset.root, false),
        )?;
        let plan = dataset_plan(dataset, spec, seed);
        self.take_spec(ctx, spec, seed, plan)
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
        settings::check(spec, &settings::frames_in_memory(source.has_depth()))?;
        let plan = FramePlan::images_at(source.frame_numbers(), source.has_depth(), spec, seed);
        let origin = Origin::Buffers;
        Ok(Self {
            pipeline: Pipeline::new(ctx, source, spec, seed)?,
            plan,
            spec: spec.clone(),
            seed,
            origin,
            generation: 0,
        })
    }

    /// Other frames of the same size through the same perturbations: the GPU pipelines built by
    /// [`FramesInMemory::buffers`] are kept, the plan is made anew for the new frame numbers.
    pub fn set_frames(&mut self, source: BufferSource) -> Result<(), PipelineError> {
        let (width, height) = self.pipeline.source().size();
        if source.size() != (width, height) {
            let (w, h) = source.size();
            return Err(PipelineError::option(
                JobPart::Frames,
                format!("{w}x{h} frames given to perturbations built for {width}x{height}"),
            ));
        }
        settings::check(&self.spec, &settings::frames_in_memory(source.has_depth()))?;
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

impl FramesInMemory<BufferSource> {
    /// Another spec and seed (image and depth corruptions only).
    pub fn set_spec(
        &mut self,
        ctx: &GpuContext,
        spec: &PerturbSpec,
        seed: u64,
    ) -> Result<(), PipelineError> {
        let source = self.pipeline.source();
        settings::check(spec, &settings::frames_in_memory(source.has_depth()))?;
        let plan = FramePlan::images_at(source.frame_numbers(), source.has_depth(), spec, seed);
        self.take_spec(ctx, spec, seed, plan)
    }
}

impl<S: FrameSource> FramesInMemory<S> {
    pub fn plan(&self) -> &FramePlan {
        &self.plan
    }

    pub fn spec(&self) -> &PerturbSpec {
        &self.spec
    }

    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// Width and height of every frame.
    pub fn size(&self) -> (u32, u32) {
        self.pipeline.source().size()
    }

    fn take_spec(
        &mut self,
        ctx: &GpuContext,
        spec: &PerturbSpec,
        seed: u64,
        plan: FramePlan,
    ) -> Result<(), PipelineError> {
        self.pipeline.set_spec(ctx, spec, seed)?;
        self.plan = plan;
        self.spec = spec.clone();
        self.seed = seed;
        Ok(())
    }

    /// The source frames output frame `index` is made of.
    pub fn output_sources(&self, index: usize) -> Result<ShownSources, PipelineError> {
        if index >= self.plan.len() {
            return Err(PipelineError::option(
                JobPart::Frame,
                format!("{index} is past the {} output frames", self.plan.len()),
            ));
        }
        Ok(ShownSources {
            rgb: self.plan.rgb_source[index],
            depth: self
                .plan
                .depth_source
                .get(index)
                .copied()
                .unwrap_or(self.plan.rgb_source[index]),
        })
    }

    /// Output frame `index` left on the GPU in `shown`, clean and perturbed, its depth
    /// colour-mapped at `range`: what [`FramesInMemory::frame`] returns, without the readback.
    /// Source frames `shown` holds already are not drawn again (a spec change re-perturbs only).
    pub fn show(
        &mut self,
        ctx: &GpuContext,
        index: usize,
        shown: &mut ShownFrame,
        range: DepthRange,
    ) -> Result<(), PipelineError> {
        if shown.size() != self.size() {
            return Err(PipelineError::option(
                JobPart::Frame,
                format!(
                    "shown frame is {:?}, the frames are {:?}",
                    shown.size(),
                    self.size()
                ),
            ));
        }
        let held = Held {
            sources: self.output_sources(index)?,
            pose: None,
            generation: self.generation,
        };
        self.pipeline
            .show_with(ctx, held, shown, range, |source, encoder, frame, i| {
                source.record(ctx, encoder, frame, i)
            })
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
                JobPart::Frames,
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
