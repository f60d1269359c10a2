use std::path::PathBuf;

use anyhow::Context;
use rslam_core::dataset::{DatasetFormat, DatasetWriter};
use rslam_core::trajectory_io::read_trajectory;
use rslam_core::{Intrinsics, Trajectory};
use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_perturb::{PerturbSpec, Perturber};
use rslam_render::{load_scene, Rasterizer};

use super::drive::drive;
use super::manifest::ManifestBuilder;
use super::sink::{FrameSink, OutputPlan};

/// Everything `rslam render` needs, validated.
pub struct RenderJob {
    pub scene: String,
    pub out: PathBuf,
    pub trajectory: Option<PathBuf>,
    pub frames: Option<usize>,
    pub camera: Intrinsics,
    pub rate_hz: f64,
    pub format: DatasetFormat,
    pub seed: u64,
    pub perturb: PerturbSpec,
    pub adapter: AdapterChoice,
    pub command: Vec<String>,
}

pub struct RenderReport {
    pub frames: usize,
    pub frames_per_second: f64,
}

fn camera_path(job: &RenderJob, scene_path: &Option<Trajectory>) -> anyhow::Result<Trajectory> {
    let poses = match &job.trajectory {
        Some(path) => read_trajectory(path, None)?.trajectory.poses,
        None => scene_path
            .as_ref()
            .map(|t| t.poses.clone())
            .with_context(|| {
                format!(
                    "scene '{}' has no default trajectory: pass --traj FILE",
                    job.scene
                )
            })?,
    };
    let count = match job.frames {
        Some(n) if n > poses.len() => anyhow::bail!(
            "--frames {n}: the trajectory has only {} poses",
            poses.len()
        ),
        Some(0) => anyhow::bail!("--frames 0: expected at least one frame"),
        Some(n) => n,
        None => poses.len(),
    };
    Ok(Trajectory::from_poses_at_rate(
        poses[..count].to_vec(),
        job.rate_hz,
    ))
}

pub fn run_render(job: RenderJob) -> anyhow::Result<RenderReport> {
    let ctx = GpuContext::new(&job.adapter)?;
    eprintln!("adapter: {}", ctx.describe());
    let scene = load_scene(&job.scene)?;
    let clean = camera_path(&job, &scene.default_trajectory)?;
    let deviated = rslam_perturb::trajectory::deviate(&clean, &job.perturb, job.seed);
    let stream = rslam_perturb::stream::plan(deviated.len(), &job.perturb, job.seed);
    let rate = job.rate_hz;
    let plan = OutputPlan::new(
        stream.rgb_source,
        stream.depth_source,
        |j| j as f64 / rate,
        |_| 0.0,
    );
    let k = job.camera;
    let rasterizer = Rasterizer::new(&ctx, &scene, k)?;
    let mut perturber = Perturber::new(&ctx, &job.perturb, k.width, k.height, job.seed)?;
    let writer = DatasetWriter::create(&job.out, job.format, k)?;
    let sink = FrameSink::new(writer, plan);
    let frames_per_second = drive(&ctx, &sink, true, "rendering", |source, encoder, frame| {
        rasterizer.encode(&ctx, encoder, frame, &deviated.poses[source]);
        perturber.encode(&ctx, encoder, frame, source as u32)?;
        Ok(())
    })?;
    let ground_truth = sink.plan().ground_truth(&deviated.poses);
    let manifest = ManifestBuilder {
        command: &job.command,
        source: &scene.name,
        source_hash: scene.content_hash(),
        format: job.format,
        camera: k,
        rate_hz: job.rate_hz,
        seed: job.seed,
        spec: &job.perturb,
        perturber: &perturber,
        plan: sink.plan(),
        extra: serde_json::json!({ "adapter": ctx.describe() }),
    }
    .build()?;
    let frames = manifest.frame_count;
    sink.finish(&ground_truth, &manifest)?;
    Ok(RenderReport {
        frames,
        frames_per_second,
    })
}
