//! The world items on a scene job: a user's actors (a rigid mesh along a path file each, checked
//! against the scene and the camera's path), and walkers and moved objects planned once per job
//! from the spec, the seed and the camera's path (so every camera of a rig sees the same people
//! and things at the same instant), giving way to the user's actors; refused for a scene
//! without a free floor, and recorded in the manifest (`extra.actors`: each walker's build, and
//! per frame its position, heading and gait phase; each object's kind and when it moves; each
//! user's actor's files and their BLAKE3; per frame every rigid actor's pose).

use std::sync::Arc;

use rslam_core::Pose;
use rslam_perturb::{Need, PerturbSpec};
use rslam_render::actors::{
    Actors, CameraTrack, ObjectParams, RigidActor, RigidOrigin, WalkerParams, World,
};
use rslam_render::Scene;

use crate::plan::FramePlan;
use crate::scene_job::ActorFiles;
use crate::{settings, PipelineError};

/// The user's actors of `files` and the walkers and objects of `spec`, along `poses` (source
/// frames at `rate_hz`, before `fast`); `None` without any.
pub fn plan(
    scene: &Scene,
    (spec, files): (&PerturbSpec, &[ActorFiles]),
    seed: u64,
    poses: &[Pose],
    rate_hz: f64,
) -> Result<Option<Arc<Actors>>, PipelineError> {
    if spec.world.is_empty() && files.is_empty() {
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
    let user = (files.iter())
        .map(|f| RigidActor::load(&f.mesh, &f.path))
        .collect::<Result<Vec<_>, _>>()?;
    let walkers = spec.world.actors.map(|w| WalkerParams {
        count: w.count,
        speed_m_s: w.speed_m_s as f32,
        near_m: w.near_m as f32,
        ahead_m: w.ahead_m.map(|a| a as f32),
    });
    let objects = spec.world.objects.map(|o| ObjectParams {
        count: o.count,
        speed_m_s: o.speed_m_s as f32,
        near_m: o.near_m as f32,
    });
    let world = World {
        walkers: walkers.as_ref(),
        objects: objects.as_ref(),
        user,
    };
    Ok(Some(Arc::new(Actors::plan(scene, world, seed, &camera)?)))
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
                "closest_in_view_m": w.closest_in_view_m.map(round),
                "walking_share": round(w.walking_share),
                "in_view_share": round(w.in_view_share),
                "ahead_m": w.ahead_m.map(round),
                "top": w.top,
                "carries_box": w.body.carries(),
            })
        })
        .collect();
    let (mut user, mut objects) = (Vec::new(), Vec::new());
    for a in actors.rigid_actors() {
        match &a.origin {
            RigidOrigin::Files {
                mesh_file,
                path_file,
                mesh_blake3,
                path_blake3,
                ..
            } => user.push(serde_json::json!({
                "mesh": mesh_file.display().to_string(),
                "mesh_blake3": mesh_blake3,
                "path": path_file.display().to_string(),
                "path_blake3": path_blake3,
                "footprint_radius_m": round(a.radius),
            })),
            RigidOrigin::Object(object) => objects.push(serde_json::json!({
                "kind": object.kind,
                "moves_s": (object.moves.iter())
                    .map(|m| m.map(|t| (t * 1e4).round() / 1e4))
                    .collect::<Vec<_>>(),
                "footprint_radius_m": round(a.radius),
                "closest_to_camera_m": round(object.closest_m),
            })),
        }
    }
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
    let rigid_frames: Vec<Vec<[f64; 7]>> = (plan.frames.iter())
        .map(|frame| {
            (actors.rigid_actors().iter())
                .map(|a| {
                    let (turn, at) = a.pose_at(frame.rgb_time);
                    let [x, y, z] = at.to_array().map(round);
                    let [qx, qy, qz, qw] = turn.to_array().map(round);
                    [x, y, z, qx, qy, qz, qw]
                })
                .collect()
        })
        .collect();
    extra["actors"] = serde_json::json!({
        "walkers": walkers,
        "objects": objects,
        "user": user,
        "frame_fields": ["x_m", "y_m", "heading_rad", "gait_phase", "step_m"],
        "frames": frames,
        "rigid_frame_fields": ["x_m", "y_m", "z_m", "qx", "qy", "qz", "qw"],
        "rigid_frames": rigid_frames,
    });
}
