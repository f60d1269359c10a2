//! The light items on a scene job: refused for a scene without light layers, scheduled from the
//! spec and seed over the scene's layers ([`LightSchedule`]), and recorded per output frame in
//! the manifest (`extra.light`: each layer's name and its RGB weight per frame, over the frame's
//! exposure at its timestamp; under a rolling shutter other rows see other instants).

use rslam_perturb::light::{LayerKind, LightSchedule};
use rslam_perturb::sensor::Shutter;
use rslam_perturb::{Need, PerturbSpec};
use rslam_render::{LightKind, Scene};

use crate::plan::FramePlan;
use crate::{settings, PipelineError};

/// Refuses light items for a scene whose light is not kept as layers.
pub fn check(scene: &Scene, spec: &PerturbSpec) -> Result<(), PipelineError> {
    if scene.lights.is_some() {
        return Ok(());
    }
    let light_only = PerturbSpec {
        light: spec.light,
        ..PerturbSpec::default()
    };
    settings::check(&light_only, &settings::scene_file(scene, Need::LightLayers))
}

/// The schedule of `spec`'s light items over `horizon` seconds; `None` without light items.
pub fn schedule(
    scene: &Scene,
    spec: &PerturbSpec,
    seed: u64,
    horizon: f64,
) -> Result<Option<LightSchedule>, PipelineError> {
    if spec.light.is_empty() {
        return Ok(None);
    }
    check(scene, spec)?;
    Ok(Some(LightSchedule::new(
        &spec.light,
        seed,
        &layer_kinds(scene),
        horizon,
    )))
}

fn layer_kinds(scene: &Scene) -> Vec<LayerKind> {
    let kinds = scene.lights.as_ref().map(|l| l.kinds.as_slice());
    kinds
        .unwrap_or_default()
        .iter()
        .map(|k| match k {
            LightKind::Lamp => LayerKind::Lamp,
            LightKind::Daylight => LayerKind::Daylight,
        })
        .collect()
}

/// Puts each output frame's light state into the manifest's `extra.light`, if `spec` has light
/// items.
pub fn record(
    extra: &mut serde_json::Value,
    scene: &Scene,
    spec: &PerturbSpec,
    seed: u64,
    plan: &FramePlan,
) -> Result<(), PipelineError> {
    let horizon = plan.frames.last().map_or(0.0, |f| f.rgb_time) + 1.0;
    let Some(schedule) = schedule(scene, spec, seed, horizon)? else {
        return Ok(());
    };
    let (a, b) = Shutter::of(spec).window();
    let round = |w: f32| (f64::from(w) * 1e4).round() / 1e4;
    let frames: Vec<Vec<[f64; 3]>> = plan
        .frames
        .iter()
        .map(|f| {
            let weights = schedule.weights(f.rgb_time + a, f.rgb_time + b);
            weights.iter().map(|w| w.map(round)).collect()
        })
        .collect();
    let names = scene.lights.as_ref().map(|l| l.names()).unwrap_or_default();
    extra["light"] = serde_json::json!({ "layers": names, "frames": frames });
    Ok(())
}
