//! [`Job`]: the one description of what rslam makes, and [`run`], the one way to make it.
//!
//! A job is a source (a scene along a path, a recorded dataset, image files), the sensors that
//! see it and the layout they are written in, the perturbation spec and its seed, and the output
//! folder. A job is first planned on the CPU ([`Job::plan`]: the source read or loaded, every
//! refusal, the poses and frame plan, the IMU streams, the manifest), then run
//! ([`PlannedJob::run`]: what it needs of the GPU, then the output folder's one life,
//! [`make_output`]: prepared, skipped when this job finished there, written, sealed). The CLI
//! and the suite build a `Job`; the suite asks [`Job::holding`] whether a job's output is
//! finished, by the rule a run uses.

use std::path::{Path, PathBuf};

use rslam_core::dataset::ros2::{BagCompression, BagDepth, BagOptions};
use rslam_core::dataset::{DatasetFormat, DatasetOverrides, DepthPng, Layout, Manifest};
use rslam_gpu::GpuContext;
use rslam_perturb::{PerturbSpec, Setting};

use crate::output_folder::{self, make_output, FolderState, Holding, Written};
use crate::perturb_dataset::RecordedDataset;
use crate::progress::Progress;
use crate::rig::{CameraFrames, Rig, RigPreset};
use crate::scene_job::{SceneCache, SceneJob};
use crate::settings;
use crate::{perturb_bag, perturb_dataset, perturb_images, render, rig, JobPart, PipelineError};

/// What to make, and where.
#[derive(Clone, Debug)]
pub struct Job {
    pub source: Source,
    /// The output folder (with [`Source::Image`], the output file).
    pub out: PathBuf,
    /// Replace whatever rslam output `out` holds.
    pub force: bool,
    /// How the job was asked for (the command as typed), recorded in the manifest; not part of
    /// what the job is.
    pub command: Vec<String>,
}

/// Where a job's frames come from, and what perturbs them.
// One per dataset made: the size of the scene variant does not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub enum Source {
    /// A scene along its path (the scene job holds the spec and seed), seen by `sensors`.
    Scene { scene: SceneJob, sensors: Sensors },
    /// A recorded RGB-D dataset (Replica or TUM layout, with the IMU of an `rgbd-imu` output),
    /// copied in its layout with its frames perturbed.
    Dataset {
        input: PathBuf,
        /// Camera and rate where the dataset does not state them.
        overrides: DatasetOverrides,
        /// How the output's depth PNGs are compressed.
        depth_png: DepthPng,
        spec: PerturbSpec,
        seed: u64,
    },
    /// A recorded EuRoC dataset (the folder holding `mav0/`, or `mav0/`; also TUM-VI's
    /// EuRoC-style export), copied with its frames and IMU perturbed.
    Euroc {
        input: PathBuf,
        spec: PerturbSpec,
        seed: u64,
    },
    /// A recorded ROS 2 bag (a rosbag2 folder), copied into a bag with its camera's images
    /// perturbed; each topic keeps its encoding and the recorded `/tf`, so of a bag's options
    /// only the chunks' compression is the job's to choose.
    Bag {
        input: PathBuf,
        compression: BagCompression,
        spec: PerturbSpec,
        seed: u64,
    },
    /// Image files, image i frame i, perturbed into the output folder under their own names.
    Images {
        files: Vec<PathBuf>,
        spec: PerturbSpec,
        seed: u64,
    },
    /// One image perturbed into the output file (no folder, no manifest).
    Image {
        file: PathBuf,
        spec: PerturbSpec,
        seed: u64,
    },
}

/// What sees a scene, which decides the layout it is written in.
// One per job: the size of the rig variant does not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub enum Sensors {
    /// One RGB-D camera (the scene job's) in a core layout.
    Camera {
        format: DatasetFormat,
        depth_png: DepthPng,
        bag: BagOptions,
    },
    /// `rgbd-imu`: that camera on a RealSense D435i-like body with its IMU, in the TUM layout
    /// with `imu0/` and the body's ground truth beside it, or in a ROS 2 bag with `/imu0`.
    CameraImu {
        format: DatasetFormat,
        depth_png: DepthPng,
        bag: BagOptions,
    },
    /// A rig of cameras and an IMU, in the EuRoC layout or a ROS 2 bag (`Layout::Camera(Ros2)`).
    Rig(Rig, Layout, BagOptions),
}

impl Sensors {
    /// What `preset` is when written in `layout`: the one place where rigs meet layouts.
    /// `depth_png` applies to the layouts with depth, `bag` to a ROS 2 bag (its depth option to
    /// one with depth).
    pub fn new(
        preset: RigPreset,
        layout: Layout,
        depth_png: DepthPng,
        bag: BagOptions,
    ) -> Result<Self, PipelineError> {
        if !bag.is_default() && layout != Layout::Camera(DatasetFormat::Ros2) {
            return Err(PipelineError::option(
                JobPart::Bag,
                format!("applies to a ROS 2 bag, not the {layout} layout"),
            ));
        }
        let rig = match (preset, layout) {
            (RigPreset::Rgbd, Layout::Camera(format)) => {
                return Ok(Self::Camera {
                    format,
                    depth_png,
                    bag,
                })
            }
            (
                RigPreset::RgbdImu,
                Layout::Camera(format @ (DatasetFormat::Tum | DatasetFormat::Ros2)),
            ) => {
                return Ok(Self::CameraImu {
                    format,
                    depth_png,
                    bag,
                })
            }
            (RigPreset::Euroc(_), _) if bag.depth != BagDepth::default() => {
                return Err(PipelineError::option(
                    JobPart::Bag,
                    format!("{} depth: a rig of cameras has no depth", bag.depth),
                ))
            }
            (RigPreset::Euroc(rig), Layout::Euroc | Layout::Camera(DatasetFormat::Ros2)) => {
                return Ok(Self::Rig(rig, layout, bag))
            }
            (RigPreset::Rgbd, _) => "rgbd".to_string(),
            (RigPreset::RgbdImu, _) => "rgbd-imu".to_string(),
            (RigPreset::Euroc(rig), _) => rig.name,
        };
        Err(PipelineError::RigLayout { rig, layout })
    }

    /// What these sensors offer a spec's items ([`settings`]).
    pub fn setting(&self) -> Setting {
        match self {
            Self::Camera { .. } => settings::one_camera_render("a one-camera render"),
            Self::CameraImu { .. } => settings::rgbd_imu_render(),
            Self::Rig(rig, ..) => settings::euroc_rig_render(rig),
        }
    }

    /// Refuses the first item of `spec` these sensors cannot take.
    pub fn check_spec(&self, spec: &PerturbSpec) -> Result<(), PipelineError> {
        settings::check(spec, &self.setting())
    }

    pub fn layout(&self) -> Layout {
        match self {
            Self::Camera { format, .. } => Layout::Camera(*format),
            Self::CameraImu { format, .. } => Layout::Camera(*format),
            Self::Rig(_, layout, _) => *layout,
        }
    }
}

/// What a job's output holds.
#[derive(Clone, Debug, PartialEq)]
pub enum Streams {
    /// One camera's output frames: a Replica or TUM dataset (with `rgbd-imu`, its IMU beside),
    /// a folder of images, one image.
    Frames(usize),
    /// Each camera's frames and the IMU samples of a rig, in the EuRoC layout.
    Rig {
        cameras: Vec<CameraFrames>,
        imu_samples: usize,
    },
}

/// What a run did.
#[derive(Clone, Debug, PartialEq)]
pub struct JobReport {
    pub streams: Streams,
    /// Source frames drawn (or perturbed, or copied) by this run, all cameras together: fewer
    /// than the output holds when it resumed, none when the folder was complete already.
    pub made: usize,
    /// What the output folder held when the run began.
    pub found: FolderState,
    /// The manifest as written (as found, when the folder was complete already); `None` for one
    /// image.
    pub manifest: Option<Manifest>,
}

/// A job made concrete on the CPU: its manifest, and what writing its output takes.
pub(crate) trait Planned {
    /// The job's manifest, without the content digest and the GPU it runs on.
    fn manifest(&self) -> &Manifest;
    fn streams(&self) -> Streams;
    /// What writes the output, with what it needs of the GPU made first, before the output
    /// folder is touched (a job the GPU refuses leaves no trace).
    fn open<'a>(&'a self, ctx: &'a GpuContext) -> Result<Writing<'a>, PipelineError>;
}

/// Writes the output into the prepared folder (`found`: `Fresh`, or `Resume` with the files an
/// unfinished run finished), sealing it with the manifest.
pub(crate) type Writing<'a> = Box<
    dyn FnOnce(&Path, FolderState, Manifest, &dyn Progress) -> Result<Written, PipelineError> + 'a,
>;

/// A [`Job`] planned: everything of it that needs no GPU done, every refusal of its source,
/// sensors and spec made.
pub struct PlannedJob<'a> {
    job: &'a Job,
    plan: Plan<'a>,
}

enum Plan<'a> {
    /// An output folder, written by its plan inside the folder's one life.
    Folder(Box<dyn Planned + 'a>),
    /// One image perturbed into one file: no folder, no manifest.
    Image {
        file: &'a Path,
        spec: &'a PerturbSpec,
        seed: u64,
    },
}

impl Job {
    /// Plans the job on the CPU: reads or loads its source, refuses what its sensors and layout
    /// cannot take, makes the poses, frame plan and IMU streams, and the manifest.
    pub fn plan(&self) -> Result<PlannedJob<'_>, PipelineError> {
        self.plan_with(&SceneCache::default())
    }

    /// Like [`Job::plan`], a scene taken from `scenes` (loaded there on first use).
    pub fn plan_with(&self, scenes: &SceneCache) -> Result<PlannedJob<'_>, PipelineError> {
        let command = &self.command;
        let planned: Box<dyn Planned + '_> = match &self.source {
            Source::Image { file, spec, seed } => {
                settings::check(spec, &settings::image_files())?;
                return Ok(PlannedJob {
                    job: self,
                    plan: Plan::Image {
                        file,
                        spec,
                        seed: *seed,
                    },
                });
            }
            Source::Scene { scene, sensors } => {
                sensors.check_spec(&scene.spec)?;
                match sensors {
                    Sensors::Camera {
                        format,
                        depth_png,
                        bag,
                    } => Box::new(render::plan(
                        scene, *format, *depth_png, *bag, command, scenes,
                    )?),
                    Sensors::CameraImu {
                        format,
                        depth_png,
                        bag,
                    } => Box::new(rig::rgbd_imu_render::plan(
                        scene, *format, *depth_png, *bag, command, scenes,
                    )?),
                    Sensors::Rig(rig, layout, bag) => Box::new(rig::euroc_render::plan(
                        scene, rig, *layout, *bag, command, scenes,
                    )?),
                }
            }
            Source::Dataset {
                input,
                overrides,
                depth_png,
                spec,
                seed,
            } => Box::new(perturb_dataset::plan(
                RecordedDataset {
                    input,
                    overrides,
                    depth_png: *depth_png,
                    spec,
                    seed: *seed,
                },
                command,
            )?),
            Source::Euroc { input, spec, seed } => {
                Box::new(rig::euroc_perturb::plan(input, spec, *seed, command)?)
            }
            Source::Bag {
                input,
                compression,
                spec,
                seed,
            } => Box::new(perturb_bag::plan(
                input,
                *compression,
                spec,
                *seed,
                command,
            )?),
            Source::Images { files, spec, seed } => {
                Box::new(perturb_images::plan(files, spec, *seed, command)?)
            }
        };
        Ok(PlannedJob {
            job: self,
            plan: Plan::Folder(planned),
        })
    }

    /// What the output folder holds for this job, by the rule a run uses
    /// ([`output_folder::holding`]); the job is planned only when the folder holds a record to
    /// compare it with. Without a GPU at hand (`adapter` `None`) an output counts as this job's
    /// when it is this job's on the GPU that made it (the one its record names).
    pub fn holding(
        &self,
        adapter: Option<&str>,
        scenes: &SceneCache,
    ) -> Result<Holding, PipelineError> {
        output_folder::holding(&self.out, |earlier| {
            let recorded = earlier.extra.get("adapter").and_then(|a| a.as_str());
            self.manifest_on(adapter.or(recorded).unwrap_or_default(), scenes)
        })
    }

    /// The manifest (without its content digest) this job writes on the GPU described as
    /// `adapter`, its scene taken from `scenes`.
    pub fn manifest_on(
        &self,
        adapter: &str,
        scenes: &SceneCache,
    ) -> Result<Manifest, PipelineError> {
        match &self.plan_with(scenes)?.plan {
            Plan::Folder(planned) => Ok(PlannedJob::manifest_on(planned.as_ref(), adapter)),
            Plan::Image { .. } => Err(PipelineError::output(
                &self.out,
                "one image is written as a file, not into an output folder",
            )),
        }
    }

    /// The input folder a perturbing job reads, which its output may not be.
    fn input(&self) -> Option<&Path> {
        match &self.source {
            Source::Dataset { input, .. }
            | Source::Euroc { input, .. }
            | Source::Bag { input, .. } => Some(input),
            Source::Images { files, .. } => files.first().and_then(|f| f.parent()),
            Source::Scene { .. } | Source::Image { .. } => None,
        }
    }
}

impl PlannedJob<'_> {
    /// The job's manifest on the GPU described as `adapter` (the manifest records it: another
    /// GPU's float rounding writes other bytes).
    fn manifest_on(planned: &dyn Planned, adapter: &str) -> Manifest {
        let mut manifest = planned.manifest().clone();
        manifest.extra["adapter"] = adapter.into();
        manifest
    }

    /// Makes the job on `ctx`: what it needs of the GPU first, then its output folder's one
    /// life, written by the plan.
    pub fn run(
        &self,
        ctx: &GpuContext,
        progress: &dyn Progress,
    ) -> Result<JobReport, PipelineError> {
        let job = self.job;
        let planned = match &self.plan {
            Plan::Folder(planned) => planned,
            Plan::Image { file, spec, seed } => {
                perturb_images::perturb_one(ctx, file, &job.out, spec, *seed, progress)?;
                return Ok(JobReport {
                    streams: Streams::Frames(1),
                    made: 1,
                    found: FolderState::Fresh,
                    manifest: None,
                });
            }
        };
        if let Some(input) = job.input() {
            output_folder::check_not_input(&job.out, input)?;
        }
        let write = planned.open(ctx)?;
        let made = make_output(
            &job.out,
            Self::manifest_on(planned.as_ref(), &ctx.describe()),
            job.force,
            |found, manifest| write(&job.out, found, manifest, progress),
        )?;
        Ok(JobReport {
            streams: planned.streams(),
            made: made.made,
            found: made.found,
            manifest: Some(made.manifest),
        })
    }
}

/// Plans `job`, then makes it on `ctx`.
pub fn run(
    ctx: &GpuContext,
    job: &Job,
    progress: &dyn Progress,
) -> Result<JobReport, PipelineError> {
    job.plan()?.run(ctx, progress)
}
