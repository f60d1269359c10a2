use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Context};
use rslam_core::Intrinsics;
use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_perturb::PerturbSpec;
use rslam_pipeline::SceneJob;
use rslam_viewer::{run_window, ViewOptions, ViewSource, WindowOptions};

use super::actor_args::ActorArgs;

#[derive(clap::Args)]
pub struct ViewArgs {
    /// A dataset folder (Replica or TUM layout) to view; or give --scene.
    dataset: Option<PathBuf>,
    /// Built-in scene (room0 room1 room2 office0 … office4) or a mesh file (.ply, .gltf, .glb, .obj).
    #[arg(long, conflicts_with = "dataset")]
    scene: Option<String>,
    /// Camera path of the scene: Replica traj.txt or a TUM trajectory; default: the scene's own.
    #[arg(long, requires = "scene")]
    traj: Option<PathBuf>,
    /// Use only the first N poses of the scene's path.
    #[arg(long, requires = "scene")]
    frames: Option<usize>,
    /// Scene camera: `replica` (1200x680, f=600, 20 Hz), `tum` (640x480, f=525, 30 Hz) or W,H,FX,FY,CX,CY.
    #[arg(long, default_value = "replica")]
    camera: String,
    /// Scene frame rate in Hz; default: 30 for the tum camera, else 20.
    #[arg(long, requires = "scene")]
    rate: Option<f64>,
    /// An estimated trajectory (TUM, Replica, KITTI, EuRoC) to align to the ground truth and
    /// colour by its error.
    #[arg(long)]
    estimate: Option<PathBuf>,
    /// Perturbations to start with, e.g. `fog:3,depth_missing:5` (see `rslam list`).
    #[arg(long)]
    perturb: Option<String>,
    #[command(flatten)]
    actors: ActorArgs,
    /// Seed of every random draw.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Use the GPU whose name contains this text (default: a real GPU if any, else lavapipe).
    #[arg(long)]
    adapter: Option<String>,
    /// Window width and height in points.
    #[arg(long, num_args = 2, value_names = ["WIDTH", "HEIGHT"], default_values_t = [1600.0, 900.0])]
    window: Vec<f32>,
    /// Save a PNG of the window once the first frame is shown, then close (for docs and CI).
    #[arg(long)]
    screenshot: Option<PathBuf>,
}

pub fn run(args: ViewArgs) -> anyhow::Result<ExitCode> {
    let spec = match &args.perturb {
        Some(text) => PerturbSpec::parse(text).context("--perturb")?,
        None => PerturbSpec::default(),
    };
    let source = match (args.dataset, args.scene) {
        (Some(dataset), None) => {
            if !dataset.is_dir() {
                bail!("{}: no such dataset folder", dataset.display());
            }
            ViewSource::Dataset(dataset)
        }
        (None, Some(scene)) => ViewSource::Scene(Box::new(SceneJob {
            scene,
            trajectory: args.traj,
            frames: args.frames,
            camera: Intrinsics::parse(&args.camera).context("--camera")?,
            rate_hz: args
                .rate
                .unwrap_or(Intrinsics::preset_rate_hz(&args.camera)),
            spec: spec.clone(),
            seed: args.seed,
            agent: None,
            capture: Default::default(),
            actor_files: args.actors.files(),
        })),
        _ => bail!("give a DATASET folder or --scene NAME|MESH"),
    };
    if let Some(estimate) = &args.estimate {
        if !estimate.is_file() {
            bail!("--estimate {}: no such file", estimate.display());
        }
    }
    let [width, height] = args.window[..] else {
        bail!("--window: expected WIDTH HEIGHT");
    };
    if !(width >= 200.0 && height >= 200.0) {
        bail!("--window {width} {height}: expected at least 200 200");
    }
    let ctx = GpuContext::new(&AdapterChoice {
        name_contains: args.adapter,
    })?;
    eprintln!("adapter: {}", ctx.describe());
    let view = ViewOptions {
        source,
        spec,
        seed: args.seed,
        estimate: args.estimate,
    };
    let window = WindowOptions {
        size: [width, height],
        screenshot: args.screenshot,
    };
    run_window(ctx, view, window).context("rslam view")?;
    Ok(ExitCode::SUCCESS)
}
