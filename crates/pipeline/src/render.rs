//! A scene seen by one RGB-D camera along its path, perturbed, written as a Replica or TUM
//! dataset.

use rslam_core::dataset::ros2::BagOptions;
use rslam_core::dataset::{DatasetFormat, DepthPng, Manifest};
use rslam_core::Trajectory;
use rslam_gpu::GpuContext;

use crate::agents::record_agent;
use crate::dataset_run::{dataset_writing, DatasetOutput};
use crate::job::{Planned, Streams, Writing};
use crate::manifest::ManifestParts;
use crate::pipeline::Pipeline;
use crate::scene_job::{ResolvedScene, SceneCache, SceneJob};
use crate::source::SceneSource;
use crate::PipelineError;
use crate::{scene_actors, scene_light};

/// A one-camera render, planned: the scene loaded, its poses deviated, the frame plan made.
pub(crate) struct CameraRender<'a> {
    scene: &'a SceneJob,
    format: DatasetFormat,
    resolved: ResolvedScene,
    ground_truth: Trajectory,
    manifest: Manifest,
}

pub(crate) fn plan<'a>(
    scene: &'a SceneJob,
    format: DatasetFormat,
    depth_png: DepthPng,
    bag: BagOptions,
    command: &[String],
    scenes: &SceneCache,
) -> Result<CameraRender<'a>, PipelineError> {
    let resolved = scene.resolve_in(scenes)?;
    let ground_truth = resolved.plan.ground_truth(&resolved.poses);
    let mut extra = serde_json::json!({});
    record_agent(&mut extra, scene);
    scene.record_capture(&mut extra, &resolved.scene);
    scene_light::record(
        &mut extra,
        &resolved.scene,
        &scene.spec,
        scene.seed,
        &resolved.plan,
    )?;
    scene_actors::record(&mut extra, resolved.actors.as_deref(), &resolved.plan);
    let manifest = ManifestParts {
        command,
        source: resolved.scene.name.clone(),
        source_hash: resolved.source_hash().to_string(),
        format: Some(format),
        camera: Some(scene.camera),
        distortion: scene.spec.distortion,
        depth_png,
        bag,
        rate_hz: scene.rate_hz,
        seed: scene.seed,
        spec: &scene.spec,
        plan: &resolved.plan,
        extra,
    }
    .build()?;
    Ok(CameraRender {
        scene,
        format,
        resolved,
        ground_truth,
        manifest,
    })
}

impl Planned for CameraRender<'_> {
    fn manifest(&self) -> &Manifest {
        &self.manifest
    }

    fn streams(&self) -> Streams {
        Streams::Frames(self.resolved.plan.len())
    }

    fn open<'a>(&'a self, ctx: &'a GpuContext) -> Result<Writing<'a>, PipelineError> {
        let (scene, resolved) = (self.scene, &self.resolved);
        let mut source = SceneSource::new(
            ctx,
            &resolved.scene,
            scene.camera,
            resolved.poses.clone(),
            scene.capture.settings,
            resolved.actors.clone(),
        )?;
        source.set_sensor(ctx, &scene.spec, scene.rate_hz, scene.seed)?;
        let pipeline = Pipeline::new(ctx, source, &scene.spec, scene.seed)?;
        let output = DatasetOutput {
            format: self.format,
            camera: scene.camera,
            plan: &resolved.plan,
            ground_truth: &self.ground_truth,
            sensor_files: &[],
            bag_imu: None,
        };
        Ok(dataset_writing(ctx, pipeline, output, "rendering"))
    }
}
