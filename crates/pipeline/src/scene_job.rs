//! A scene seen along a camera path with perturbations: what `rslam render` writes and what the
//! viewer shows. Resolving it loads the mesh, reads the path, deviates the poses (`rot`, `trans`)
//! and makes the frame plan (`fast`, `misalign`, severities).

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, OnceLock};

use rslam_core::trajectory_io::{read_trajectory_with, ReadOptions, TrajectoryFormat};
use rslam_core::{Intrinsics, Pose};
use rslam_perturb::PerturbSpec;
use rslam_render::actors::Actors;
use rslam_render::splat::CaptureOptions;
use rslam_render::{load_scene_scaled, Scene};

use crate::plan::FramePlan;
use crate::{scene_actors, JobPart, PipelineError};

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
    /// A Gaussian-splat capture's metric scale and depth rendering (meshes take the default).
    pub capture: CaptureOptions,
    /// A user's actors: each a rigid mesh moved along a path file.
    pub actor_files: Vec<ActorFiles>,
}

/// A user's actor: its mesh (PLY, OBJ or glTF) and the path it moves along (a trajectory file,
/// each pose the mesh's frame in the world).
#[derive(Clone, Debug, PartialEq)]
pub struct ActorFiles {
    pub mesh: std::path::PathBuf,
    pub path: std::path::PathBuf,
}

/// A loaded scene and its content hash, hashed on first use (the viewer never needs it).
type Loaded = (Arc<Scene>, Arc<OnceLock<String>>);

/// Scenes loaded once, each hashed at most once, for every job resolved with this cache: a
/// suite plans hundreds of jobs over a few scenes.
#[derive(Default)]
pub struct SceneCache {
    /// By name and the bits of the capture scale.
    loaded: Mutex<HashMap<(String, Option<u64>), Loaded>>,
}

impl SceneCache {
    /// The scene `name_or_path` ([`load_scene_scaled`]), loaded on first use.
    fn load(
        &self,
        name_or_path: &str,
        metres_per_unit: Option<f64>,
    ) -> Result<Loaded, PipelineError> {
        let key = (name_or_path.to_string(), metres_per_unit.map(f64::to_bits));
        let hit = self.lock().get(&key).cloned();
        if let Some(hit) = hit {
            return Ok(hit);
        }
        let loaded = (
            Arc::new(load_scene_scaled(name_or_path, metres_per_unit)?),
            Arc::default(),
        );
        self.lock().insert(key, loaded.clone());
        Ok(loaded)
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, HashMap<(String, Option<u64>), Loaded>> {
        // A panic elsewhere cannot leave a half-inserted entry: the map stays usable.
        self.loaded
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

/// A [`SceneJob`] made concrete: the mesh, one (deviated) pose per source frame, the plan.
pub struct ResolvedScene {
    pub scene: Arc<Scene>,
    hash: Arc<OnceLock<String>>,
    /// The path as given, at the job's rate, before any deviation.
    pub clean: rslam_core::Trajectory,
    pub poses: Vec<Pose>,
    pub plan: FramePlan,
    /// The people the spec's world items put in the scene, planned along `poses`.
    pub actors: Option<Arc<Actors>>,
}

impl ResolvedScene {
    /// The scene's content hash: the manifest's `source_hash`.
    pub fn source_hash(&self) -> &str {
        self.hash.get_or_init(|| self.scene.content_hash())
    }
}

/// The spec's items whose parameters are lengths: the depth corruptions, `trans`, the IMU's and
/// the rig calibration's.
fn items_in_metres(spec: &PerturbSpec) -> Vec<String> {
    let depth = spec.depth.iter().map(|item| item.name.clone());
    let trans = spec.translation.is_some().then(|| "trans".to_string());
    let imu = (!spec.imu.is_empty()).then(|| "imu items".to_string());
    let calibration = spec.calibration.iter().map(|c| c.name.clone());
    depth.chain(trans).chain(imu).chain(calibration).collect()
}

impl SceneJob {
    /// Fails when `scene` is a capture without a metric scale: `what` ("item 'trans' is", "a
    /// rig's baselines are") needs metres.
    pub(crate) fn require_metres(&self, scene: &Scene, what: &str) -> Result<(), PipelineError> {
        if scene.splats.is_none() || self.capture.metres_per_unit.is_some() {
            return Ok(());
        }
        Err(PipelineError::option(
            JobPart::CaptureScale,
            format!(
                "'{}' is a Gaussian-splat capture without a metric scale, and {what} in metres: expected the capture's metres per unit",
                self.scene
            ),
        ))
    }

    /// Writes how a capture was rendered into the manifest's `extra.capture`: its scale
    /// (metres per unit, `null` when not stated), depth and opacity threshold. Meshes write
    /// nothing.
    pub(crate) fn record_capture(&self, extra: &mut serde_json::Value, scene: &Scene) {
        if scene.splats.is_some() {
            let settings = &self.capture.settings;
            extra["capture"] = serde_json::json!({
                "metres_per_unit": self.capture.metres_per_unit,
                "depth": settings.depth.name(),
                "min_opacity": settings.min_opacity,
            });
        }
    }

    pub fn resolve(&self) -> Result<ResolvedScene, PipelineError> {
        self.resolve_in(&SceneCache::default())
    }

    /// Like [`SceneJob::resolve`], the scene taken from `scenes` (loaded there on first use).
    pub fn resolve_in(&self, scenes: &SceneCache) -> Result<ResolvedScene, PipelineError> {
        if !(self.rate_hz.is_finite() && self.rate_hz > 0.0) {
            return Err(PipelineError::option(
                JobPart::Rate,
                format!("{}: expected a positive number of Hz", self.rate_hz),
            ));
        }
        let loaded = scenes.load(&self.scene, self.capture.metres_per_unit)?;
        let clean = self.camera_path(&loaded.0)?;
        self.resolve_path(loaded, clean)
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
        let loaded = SceneCache::default().load(&self.scene, self.capture.metres_per_unit)?;
        self.resolve_path(loaded, poses)
    }

    /// The clean path deviated by the spec's `rot`/`trans`, and the plan.
    fn resolve_path(
        &self,
        (scene, hash): Loaded,
        clean: Vec<Pose>,
    ) -> Result<ResolvedScene, PipelineError> {
        if let Some(item) = items_in_metres(&self.spec).first() {
            self.require_metres(&scene, &format!("item '{item}' is"))?;
        }
        let opacity = self.capture.settings.min_opacity;
        if scene.splats.is_some() && !(0.0..=1.0).contains(&opacity) {
            return Err(PipelineError::option(
                JobPart::CaptureOpacity,
                format!("{opacity}: expected an accumulated opacity from 0 to 1"),
            ));
        }
        let clean = rslam_core::Trajectory::from_poses_at_rate(clean, self.rate_hz);
        let deviated = rslam_perturb::trajectory::deviate(&clean, &self.spec, self.seed);
        let plan = FramePlan::rendered(deviated.len(), self.rate_hz, &self.spec, self.seed);
        let actors = scene_actors::plan(
            &scene,
            (&self.spec, &self.actor_files),
            self.seed,
            &deviated.poses,
            self.rate_hz,
        )?;
        Ok(ResolvedScene {
            scene,
            hash,
            clean,
            poses: deviated.poses,
            plan,
            actors,
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
            (Some(path), None) => {
                let options = ReadOptions {
                    dataparser_transforms: self.capture.dataparser_transforms.clone(),
                    ..ReadOptions::default()
                };
                let file = read_trajectory_with(path, &options)?;
                let mut poses = file.trajectory.poses;
                // A COLMAP images.txt comes from the capture's own reconstruction, in its units.
                if let (TrajectoryFormat::Colmap, Some(scale)) =
                    (file.format, self.capture.metres_per_unit)
                {
                    poses.iter_mut().for_each(|p| p.translation *= scale);
                }
                poses
            }
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
