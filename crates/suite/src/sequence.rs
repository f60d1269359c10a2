//! One row of a suite made concrete: the dataset `datasets/<name>/` that `rslam suite run` makes,
//! as the [`Job`] it is (one RGB-D camera, that camera with an IMU, or a rig in the EuRoC
//! layout).

use std::path::{Path, PathBuf};

use rslam_core::dataset::ros2::BagOptions;
use rslam_core::dataset::{DepthPng, Layout};
use rslam_core::hash::{fnv1a64, splitmix64};
use rslam_core::trajectory_io::read_trajectory;
use rslam_core::Intrinsics;
use rslam_gpu::GpuContext;
use rslam_perturb::PerturbSpec;
use rslam_pipeline::rig::{rgbd_imu_frame_count, rig_camera_frames};
use rslam_pipeline::{
    speed_up, FolderState, FramePlan, Job, PipelineError, Progress, SceneCache, SceneJob, Sensors,
    Source,
};

use crate::SuiteError;

/// The folder of a suite that holds one dataset per sequence.
pub const DATASETS_DIR: &str = "datasets";

#[derive(Clone, Debug, PartialEq)]
pub struct Sequence {
    /// `<scene>__<setting>`: the dataset's folder name, how `rslam eval --runs` groups it.
    pub name: String,
    /// Built-in scene name, or a mesh file relative to the suite folder.
    pub scene: String,
    pub spec: PerturbSpec,
    pub seed: u64,
    /// Only the first N poses of the path; `None`: all of them.
    pub frames: Option<usize>,
    /// What sees the scene, which decides the layout.
    pub sensors: Sensors,
    /// The camera, or a rig's cam0.
    pub camera: Intrinsics,
    /// The camera as the row wrote it (`replica`, `tum` or `W,H,FX,FY,CX,CY`); `None` for a rig,
    /// whose cameras are its own.
    pub camera_text: Option<String>,
    /// The rate of the path's poses (of the camera's frames without a rig).
    pub rate_hz: f64,
    /// Camera path file relative to the suite folder; `None`: the scene's own path.
    pub traj: Option<PathBuf>,
}

/// Frames of a sequence: drawn from the scene, and written (fewer under `fast`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameCounts {
    pub rendered: usize,
    pub written: usize,
}

/// The seed of a row that names none: a function of the suite seed and the row's own name only,
/// so adding, removing or reordering rows changes no other row.
pub fn sequence_seed(suite_seed: u64, name: &str) -> u64 {
    splitmix64(suite_seed ^ fnv1a64(name.as_bytes()))
}

impl Sequence {
    /// The part of the name after `__`.
    pub fn setting(&self) -> &str {
        self.name
            .split_once("__")
            .map_or("", |(_, setting)| setting)
    }

    /// The part of the name before `__`.
    pub fn scene_label(&self) -> &str {
        self.name
            .split_once("__")
            .map_or(&self.name, |(scene, _)| scene)
    }

    pub fn layout(&self) -> Layout {
        self.sensors.layout()
    }

    pub fn dir(&self, suite_dir: &Path) -> PathBuf {
        suite_dir.join(DATASETS_DIR).join(&self.name)
    }

    /// The `rslam render` command that makes this sequence, run from the suite folder: what the
    /// manifest records as the command, so that a reader can make the sequence again by hand.
    /// Whether a sequence is complete is the job's question ([`Sequence::job`]), not this.
    pub fn command(&self) -> Vec<String> {
        self.command_to(&Path::new(DATASETS_DIR).join(&self.name))
    }

    /// [`Sequence::command`] writing to `out`.
    fn command_to(&self, out: &Path) -> Vec<String> {
        let mut args: Vec<String> = ["rslam", "render", "--scene", &self.scene]
            .map(String::from)
            .to_vec();
        let mut push = |words: &[&str]| args.extend(words.iter().map(|w| w.to_string()));
        if let Some(traj) = &self.traj {
            push(&["--traj", &traj.display().to_string()]);
        }
        if let Some(frames) = self.frames {
            push(&["--frames", &frames.to_string()]);
        }
        let bag = match &self.sensors {
            Sensors::Camera { depth_png, bag, .. } | Sensors::CameraImu { depth_png, bag, .. } => {
                if let Sensors::CameraImu { .. } = self.sensors {
                    push(&["--rig", "rgbd-imu"]);
                }
                push(&["--camera", self.camera_text.as_deref().unwrap_or_default()]);
                push(&["--rate", &self.rate_hz.to_string()]);
                push(&["--format", &self.layout().to_string()]);
                if *depth_png != DepthPng::default() {
                    push(&["--depth-png", &depth_png.to_string()]);
                }
                bag
            }
            Sensors::Rig(rig, layout, bag) => {
                push(&["--rig", &rig.name]);
                push(&["--rate", &self.rate_hz.to_string()]);
                push(&["--format", &layout.to_string()]);
                bag
            }
        };
        let default = BagOptions::default();
        if bag.depth != default.depth {
            push(&["--bag-depth", &bag.depth.to_string()]);
        }
        if bag.tf {
            push(&["--bag-tf"]);
        }
        if bag.compression != default.compression {
            push(&["--bag-compression", &bag.compression.to_string()]);
        }
        push(&["--seed", &self.seed.to_string()]);
        if !self.spec.is_empty() {
            push(&["--perturb", &self.spec.to_string()]);
        }
        push(&["--out", &out.display().to_string()]);
        args
    }

    /// The job that makes this sequence (`force`: replacing another job's output).
    pub fn job(&self, suite_dir: &Path, force: bool) -> Job {
        let scene = SceneJob {
            scene: self.scene_path(suite_dir),
            trajectory: self.traj.as_ref().map(|t| suite_dir.join(t)),
            frames: self.frames,
            camera: self.camera,
            rate_hz: self.rate_hz,
            spec: self.spec.clone(),
            seed: self.seed,
            agent: None,
            capture: Default::default(),
            actor_files: Vec::new(),
        };
        Job {
            source: Source::Scene {
                scene,
                sensors: self.sensors.clone(),
            },
            out: self.dir(suite_dir),
            force,
            command: self.command(),
        }
    }

    /// The job of this sequence's clean frames in `out`: the same poses, nothing that changes
    /// what a frame shows ([`PerturbSpec::poses_only`]).
    pub fn clean_job(&self, suite_dir: &Path, out: PathBuf) -> Job {
        let clean = Sequence {
            spec: self.spec.poses_only(),
            ..self.clone()
        };
        Job {
            command: clean.command_to(&out),
            out,
            ..clean.job(suite_dir, false)
        }
    }

    /// Renders the sequence (`force`: replacing another job's output), its scene taken from
    /// `scenes`: the frames this run made, and what the folder held before.
    pub fn render(
        &self,
        ctx: &GpuContext,
        suite_dir: &Path,
        force: bool,
        scenes: &SceneCache,
        progress: &dyn Progress,
    ) -> Result<(usize, FolderState), PipelineError> {
        self.render_into(
            ctx,
            suite_dir,
            &self.dir(suite_dir),
            force,
            scenes,
            progress,
        )
    }

    /// [`Sequence::render`] into `out` (node-local scratch) instead of the suite's folder; the
    /// manifest is the same, naming the suite's folder in its command.
    pub fn render_into(
        &self,
        ctx: &GpuContext,
        suite_dir: &Path,
        out: &Path,
        force: bool,
        scenes: &SceneCache,
        progress: &dyn Progress,
    ) -> Result<(usize, FolderState), PipelineError> {
        let job = Job {
            out: out.to_path_buf(),
            ..self.job(suite_dir, force)
        };
        let report = job.plan_with(scenes)?.run(ctx, progress)?;
        Ok((report.made, report.found))
    }

    /// Frames drawn and written (by all of a rig's cameras), from the plan, without loading
    /// the scene.
    pub fn frame_counts(&self, suite_dir: &Path) -> Result<FrameCounts, SuiteError> {
        let poses = match self.frames {
            Some(n) => n,
            None => self.path_length(suite_dir)?,
        };
        if let Sensors::Rig(rig, ..) = &self.sensors {
            let frames = rig_camera_frames(rig, poses, self.rate_hz, speed_up(&self.spec))?
                .iter()
                .map(|c| c.frames)
                .sum();
            return Ok(FrameCounts {
                rendered: frames,
                written: frames,
            });
        }
        if let Sensors::CameraImu { .. } = &self.sensors {
            let frames = rgbd_imu_frame_count(poses, self.rate_hz, speed_up(&self.spec))?;
            return Ok(FrameCounts {
                rendered: frames,
                written: frames,
            });
        }
        let plan = FramePlan::rendered(poses, self.rate_hz, &self.spec, self.seed);
        Ok(FrameCounts {
            rendered: plan.needed_sources().len(),
            written: plan.len(),
        })
    }

    fn path_length(&self, suite_dir: &Path) -> Result<usize, SuiteError> {
        if let Some(traj) = &self.traj {
            return Ok(read_trajectory(&suite_dir.join(traj), None)?
                .trajectory
                .len());
        }
        rslam_render::builtin_path_length(&self.scene).ok_or_else(|| {
            SuiteError::option(
                &format!("sequence '{}'", self.name),
                format!(
                    "scene '{}' is a mesh without a camera path: give the row a traj",
                    self.scene
                ),
            )
        })
    }

    /// What `load_scene` takes: the built-in name, or the mesh file's path.
    pub fn scene_path(&self, suite_dir: &Path) -> String {
        if rslam_render::builtin_path_length(&self.scene).is_some() {
            self.scene.clone()
        } else {
            suite_dir.join(&self.scene).display().to_string()
        }
    }
}
