//! `rslam render`: a scene along a path, perturbed, written as a dataset.

use std::path::PathBuf;

use rslam_core::dataset::{DatasetFormat, DepthPng};
use rslam_gpu::GpuContext;

use crate::agents::record_agent;
use crate::dataset_run::{write_dataset, DatasetOutput, RunReport};
use crate::manifest::ManifestParts;
use crate::pipeline::Pipeline;
use crate::progress::Progress;
use crate::scene_job::SceneJob;
use crate::source::SceneSource;
use crate::PipelineError;

pub struct RenderJob {
    pub scene: SceneJob,
    pub out: PathBuf,
    pub format: DatasetFormat,
    pub depth_png: DepthPng,
    /// Replace whatever rslam output `out` holds.
    pub force: bool,
    /// The command as typed, for the manifest.
    pub command: Vec<String>,
}

pub fn render_dataset(
    ctx: &GpuContext,
    job: &RenderJob,
    progress: &dyn Progress,
) -> Result<RunReport, PipelineError> {
    crate::rig::refuse_imu_items(&job.scene.spec, "a one-camera render")?;
    let resolved = job.scene.resolve()?;
    let camera = job.scene.camera;
    let ground_truth = resolved.plan.ground_truth(&resolved.poses);
    let mut extra = serde_json::json!({ "adapter": ctx.describe() });
    record_agent(&mut extra, &job.scene);
    let manifest = ManifestParts {
        command: &job.command,
        source: resolved.scene.name.clone(),
        source_hash: resolved.scene.content_hash(),
        format: Some(job.format),
        camera: Some(camera),
        distortion: job.scene.spec.distortion,
        depth_png: job.depth_png,
        rate_hz: job.scene.rate_hz,
        seed: job.scene.seed,
        spec: &job.scene.spec,
        plan: &resolved.plan,
        extra,
    }
    .build()?;
    let mut source = SceneSource::new(ctx, &resolved.scene, camera, resolved.poses)?;
    source.set_sensor(ctx, &job.scene.spec, job.scene.rate_hz)?;
    let mut pipeline = Pipeline::new(ctx, source, &job.scene.spec, job.scene.seed)?;
    let output = DatasetOutput {
        out: &job.out,
        format: job.format,
        camera,
        force: job.force,
        plan: &resolved.plan,
        ground_truth: &ground_truth,
        manifest,
        sensor_files: Vec::new(),
    };
    write_dataset(ctx, &mut pipeline, output, progress, "rendering")
}
