use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rslam_core::dataset::DatasetFormat;
use rslam_core::Intrinsics;
use rslam_gpu::AdapterChoice;
use rslam_perturb::PerturbSpec;

use crate::generate::{run_render, RenderJob};

#[derive(clap::Args)]
pub struct RenderArgs {
    /// Built-in scene (room0 room1 room2 office0 … office4) or a mesh file (.ply, .gltf, .glb, .obj).
    #[arg(long)]
    scene: String,
    /// Output folder (new, empty, or an earlier rslam dataset to overwrite).
    #[arg(long)]
    out: PathBuf,
    /// Camera path: Replica traj.txt or a TUM trajectory; default: the scene's own.
    #[arg(long)]
    traj: Option<PathBuf>,
    /// Render only the first N poses.
    #[arg(long)]
    frames: Option<usize>,
    /// `replica` (1200x680, f=600, 20 Hz), `tum` (640x480, f=525, 30 Hz) or W,H,FX,FY,CX,CY.
    #[arg(long, default_value = "replica")]
    camera: String,
    /// Frame rate in Hz; default: 30 for the tum camera, else 20.
    #[arg(long)]
    rate: Option<f64>,
    /// Output layout: replica (NICE-SLAM, SplaTAM, Co-SLAM, GO-SLAM) or tum (ORB-SLAM3).
    #[arg(long, default_value = "replica")]
    format: DatasetFormat,
    /// Seed of every random draw.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Perturbations, e.g. `fog:3,depth_missing:5,rot:1,fast:2` (see `rslam list`).
    #[arg(long)]
    perturb: Option<String>,
    /// Use the GPU whose name contains this text (default: a real GPU if any, else lavapipe).
    #[arg(long)]
    adapter: Option<String>,
}

pub fn run(args: RenderArgs) -> anyhow::Result<ExitCode> {
    let perturb = match &args.perturb {
        Some(text) => PerturbSpec::parse(text).context("--perturb")?,
        None => PerturbSpec::default(),
    };
    let camera = Intrinsics::parse(&args.camera).context("--camera")?;
    let default_rate = if args.camera == "tum" { 30.0 } else { 20.0 };
    let rate_hz = args.rate.unwrap_or(default_rate);
    anyhow::ensure!(
        rate_hz.is_finite() && rate_hz > 0.0,
        "--rate {rate_hz}: expected a positive number of Hz"
    );
    let job = RenderJob {
        scene: args.scene,
        out: args.out,
        trajectory: args.traj,
        frames: args.frames,
        camera,
        rate_hz,
        format: args.format,
        seed: args.seed,
        perturb,
        adapter: AdapterChoice {
            name_contains: args.adapter,
        },
        command: std::env::args().collect(),
    };
    let out = job.out.clone();
    let report = run_render(job)?;
    eprintln!(
        "wrote {} frames to {} ({:.1} frames/s)",
        report.frames,
        out.display(),
        report.frames_per_second
    );
    Ok(ExitCode::SUCCESS)
}
