//! The world items on a scene job: walkers planned once per job from the spec, the seed and the
//! camera's path (so every camera of a rig sees the same people at the same instant), or a
//! user's actors (a rigid mesh along a path file each, checked against the scene and the
//! camera's path); refused for a scene without a free floor, and recorded in the manifest
//! (`extra.actors`: each walker's build, and per frame its position, heading and gait phase; each
//! user's actor's files and their BLAKE3).

use std::sync::Arc;

use rslam_core::Pose;
use rslam_perturb::{Need, PerturbSpec};
use rslam_render::actors::{Actors, CameraTrack, RigidActor, WalkerParams};
use rslam_render::Scene;

use crate::plan::FramePlan;
use crate::scene_job::ActorFiles;
use crate::{settings, JobPart, PipelineError};

/// The walkers of `spec`, or the user's actors of `files`, along `poses` (source frames at
/// `rate_hz`, before `fast`); `None` without either.
pub fn plan(
    scene: &Scene,
    (spec, files): (&PerturbSpec, &[ActorFiles]),
    seed: u64,
    poses: &[Pose],
    rate_hz: f64,
) -> Result<Option<Arc<Actors>>, PipelineError> {
    if spec.world.actors.is_none() && files.is_empty() {
        return Ok(None);
    }
    if scene.floor.is_none() {
        let world_only = PerturbSpec {
            world: spec.world,
            ..PerturbSpec::default()
        };
        settings::check(&world_only, &settings::scene_file(scene, Need::FreeFloor))?;
    }
    let source_rate = rate_hz * f64::from(crate::plan::speed_up(spec));
    let camera = CameraTrack {
        times: (0..poses.len()).map(|i| i as f64 / source_rate).collect(),
        positions: poses.iter().map(|p| p.translation.as_vec3()).collect(),
        axes: (poses.iter())
            .map(|p| (p.rotation * glam::DVec3::Z).as_vec3())
            .collect(),
    };
    let Some(walkers) = spec.world.actors else {
        let rigid = (files.iter())
            .map(|f| RigidActor::load(&f.mesh, &f.path))
            .collect::<Result<Vec<_>, _>>()?;
        return Ok(Some(Arc::new(Actors::rigid(scene, rigid, &camera)?)));
    };
    if !files.is_empty() {
        return Err(PipelineError::option(
            JobPart::Actor,
            format!(
                "{}: walkers (actors:S) do not give way to a user's actors yet; use one or the other",
                files[0].mesh.display()
            ),
        ));
    }
    let params = WalkerParams {
        count: walkers.count,
        speed_m_s: walkers.speed_m_s as f32,
        near_m: walkers.near_m as f32,
    };
    Ok(Some(Arc::new(Actors::plan(scene, &params, seed, &camera)?)))
}

/// Puts the walkers' builds and each output frame's walker poses (at its colour's capture time,
/// the instant its source renders them at) into the manifest's `extra.actors`.
pub fn record(extra: &mut serde_json::Value, actors: Option<&Actors>, plan: &FramePlan) {
    let Some(actors) = actors else {
        return;
    };
    let round = |x: f32| (f64::from(x) * 1e4).round() / 1e4;
    let walkers: Vec<serde_json::Value> = actors
        .walkers()
        .iter()
        .map(|w| {
            serde_json::json!({
                "height_m": round(w.body.height()),
                "footprint_half_length_m": round(w.footprint.half_length),
                "footprint_radius_m": round(w.footprint.radius),
                "speed_m_s": round(w.path.speed()),
                "step_m": round(w.stride),
                "closest_to_camera_m": round(w.closest_m),
            })
        })
        .collect();
    let user: Vec<serde_json::Value> = (actors.rigid_actors().iter())
        .map(|a| {
            serde_json::json!({
                "mesh": a.mesh_file.display().to_string(),
                "mesh_blake3": a.mesh_blake3,
                "path": a.path_file.display().to_string(),
                "path_blake3": a.path_blake3,
                "footprint_radius_m": round(a.radius),
            })
        })
        .collect();
    let frames: Vec<Vec<[f64; 5]>> = (plan.frames.iter())
        .map(|frame| {
            let poses = actors.poses_at(frame.rgb_time);
            (poses.iter())
                .map(|p| {
                    let [x, y] = p.position.to_array().map(round);
                    [x, y, round(p.heading), round(p.phase), round(p.step)]
                })
                .collect()
        })
        .collect();
    extra["actors"] = serde_json::json!({
        "walkers": walkers,
        "user": user,
        "frame_fields": ["x_m", "y_m", "heading_rad", "gait_phase", "step_m"],
        "frames": frames,
    });
}
