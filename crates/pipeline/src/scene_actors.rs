//! The world items on a scene job: walkers planned once per job from the spec, the seed and the
//! camera's path (so every camera of a rig sees the same people at the same instant), refused
//! for a scene without a free floor, and recorded per output frame in the manifest
//! (`extra.actors`: each walker's build, and per frame its position, heading and gait phase).

use std::sync::Arc;

use rslam_core::Pose;
use rslam_perturb::{Need, PerturbSpec};
use rslam_render::actors::{Actors, CameraTrack, WalkerParams};
use rslam_render::Scene;

use crate::plan::FramePlan;
use crate::{settings, PipelineError};

/// The walkers of `spec` along `poses` (source frames at `rate_hz`, before `fast`); `None`
/// without world items.
pub fn plan(
    scene: &Scene,
    spec: &PerturbSpec,
    seed: u64,
    poses: &[Pose],
    rate_hz: f64,
) -> Result<Option<Arc<Actors>>, PipelineError> {
    let Some(walkers) = spec.world.actors else {
        return Ok(None);
    };
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
        "frame_fields": ["x_m", "y_m", "heading_rad", "gait_phase", "step_m"],
        "frames": frames,
    });
}
