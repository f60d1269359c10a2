//! A scene seen along a camera path with perturbations: what `rslam render` writes and what the
//! viewer shows. Resolving it loads the mesh, reads the path, deviates the poses (`rot`, `trans`)
//! and makes the frame plan (`fast`, `misalign`, severities).

use std::path::PathBuf;

use rslam_core::trajectory_io::read_trajectory;
use rslam_core::{Intrinsics, Pose};
use rslam_perturb::PerturbSpec;
use rslam_render::{load_scene, Scene};

use crate::plan::FramePlan;
use crate::{JobPart, PipelineError};

#[derive(Clone, Debug)]
pub struct SceneJob {
    /// Built-in scene name or mesh file.
    pub scene: String,
    /// Camera path file; `None`: the scene's own path.
    pub trajectory: Option<PathBuf>,
    /// Use only the first N poses.
    pub frames: Option<usize>,
    pub camera: Intrinsics,
    pub rate_hz: f64,
    pub spec: PerturbSpec,
    pub seed: u64,
    /// One agent of a multi-agent render: the built-in scene's path for that agent
    /// instead of its default one; `None` for a single camera.
    pub agent: Option<usize>,
}

/// A [`SceneJob`] made concrete: the mesh, one (deviated) pose per source frame, the plan.
pub struct ResolvedScene {
    pub scene: Scene,
    /// The path as given, at the job's rate, before any deviation.
    pub clean: rslam_core::Trajectory,
    pub poses: Vec<Pose>,
    pub plan: FramePlan,
}

impl SceneJob {
    pub fn resolve(&self) -> Result<ResolvedScene, PipelineError> {
        if !(self.rate_hz.is_finite() && self.rate_hz > 0.0) {
            return Err(PipelineError::option(
                JobPart::Rate,
                format!("{}: expected a positive number of Hz", self.rate_hz),
            ));
        }
        let scene = load_scene(&self.scene)?;
        let clean = self.camera_path(&scene)?;
        self.resolve_path(scene, clean)
    }

    /// Like [`SceneJob::resolve`], along `poses` (camera-to-world, one per frame at `rate_hz`)
    /// instead of a path file or the scene's own path; `trajectory` and `frames` are not used.
    pub fn resolve_along(&self, poses: Vec<Pose>) -> Result<ResolvedScene, PipelineError> {
        if !(self.rate_hz.is_finite() && self.rate_hz > 0.0) {
            return Err(PipelineError::option(
                JobPart::Rate,
                format!("{}: expected a positive number of Hz", self.rate_hz),
            ));
        }
        if poses.is_empty() {
            return Err(PipelineError::option(
                JobPart::Poses,
                "expected at least one pose",
            ));
        }
        self.resolve_path(load_scene(&self.scene)?, poses)
    }

    /// The clean path deviated by the spec's `rot`/`trans`, and the plan.
    fn resolve_path(&self, scene: Scene, clean: Vec<Pose>) -> Result<ResolvedScene, PipelineError> {
        let clean = rslam_core::Trajectory::from_poses_at_rate(clean, self.rate_hz);
        let deviated = rslam_perturb::trajectory::deviate(&clean, &self.spec, self.seed);
        let plan = FramePlan::rendered(deviated.len(), self.rate_hz, &self.spec, self.seed);
        Ok(ResolvedScene {
            scene,
            clean,
            poses: deviated.poses,
            plan,
        })
    }

    fn camera_path(&self, scene: &Scene) -> Result<Vec<Pose>, PipelineError> {
        let poses = match (&self.trajectory, self.agent) {
            (Some(_), Some(_)) => {
                return Err(PipelineError::option(
                    JobPart::Agents,
                    "every agent would follow the one trajectory file: leave it out, each agent walks a path of its own in a built-in scene",
                ))
            }
            (Some(path), None) => read_trajectory(path, None)?.trajectory.poses,
            (None, Some(agent)) => rslam_render::agent_trajectory(&self.scene, agent)
                .ok_or_else(|| {
                    PipelineError::option(
                        JobPart::Agents,
                        format!(
                            "scene '{}' is not a built-in one: only built-in scenes have paths for several agents",
                            self.scene
                        ),
                    )
                })?
                .poses,
            (None, None) => match &scene.default_trajectory {
                Some(path) => path.poses.clone(),
                None => {
                    return Err(PipelineError::option(
                        JobPart::Trajectory,
                        format!(
                            "scene '{}' has no default trajectory: give a trajectory file",
                            self.scene
                        ),
                    ))
                }
            },
        };
        let count = match self.frames {
            Some(0) => {
                return Err(PipelineError::option(
                    JobPart::Frames,
                    "0: expected at least one frame",
                ))
            }
            Some(n) if n > poses.len() => {
                return Err(PipelineError::option(
                    JobPart::Frames,
                    format!("{n}: the trajectory has only {} poses", poses.len()),
                ))
            }
            Some(n) => n,
            None => poses.len(),
        };
        Ok(poses[..count].to_vec())
    }
}
