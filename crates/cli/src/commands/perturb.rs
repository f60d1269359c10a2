use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rslam_core::dataset::ros2::BagCompression;
use rslam_core::dataset::{DatasetOverrides, DepthPng};
use rslam_core::Intrinsics;
use rslam_perturb::PerturbSpec;
use rslam_pipeline::{image_files, Job, PerturbInput, Source};

use super::make::make;

#[derive(clap::Args)]
pub struct PerturbArgs {
    /// A dataset (Replica, TUM or EuRoC layout: a folder holding mav0/, also TUM-VI's
    /// EuRoC-style export with dso/), a ROS 2 bag (a rosbag2 folder, MCAP storage), a folder of
    /// PNG/JPEG images, or one image.
    #[arg(long)]
    input: PathBuf,
    /// Output: a folder for datasets, bags and image folders, a file for one image (same format).
    #[arg(long)]
    out: PathBuf,
    /// Perturbations, e.g. `gaussian_noise:3,depth_missing:5,misalign:10` (see `rslam list`);
    /// on a EuRoC folder per camera (`cam1:fog:3`) and `@calibration` items
    /// (`baseline:0.01@calibration`).
    #[arg(long)]
    perturb: String,
    /// Seed of every random draw.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// The dataset's camera (`replica`, `tum` or W,H,FX,FY,CX,CY); needed when it has no
    /// rslam.json or cam_params.json (TUM sequences never do).
    #[arg(long)]
    camera: Option<String>,
    /// The dataset's frame rate in Hz; needed when it has no rslam.json and no timestamps
    /// (Replica frames).
    #[arg(long)]
    rate: Option<f64>,
    /// Depth PNG compression of a dataset's output: `fast` (default), or `small` (about a third of
    /// the size for 2–3× the encoding time; lossless either way, see docs/src/formats.md, "Depth PNGs").
    #[arg(long)]
    depth_png: Option<DepthPng>,
    /// A bag's MCAP chunks: `none` (default), `zstd` or `lz4`.
    #[arg(long)]
    bag_compression: Option<BagCompression>,
    /// Replace what --out holds if it is another rslam output (never a folder of other files).
    #[arg(long)]
    force: bool,
    /// Use the GPU whose name contains this text (default: a real GPU if any, else lavapipe).
    #[arg(long)]
    adapter: Option<String>,
}

pub fn run(args: PerturbArgs) -> anyhow::Result<ExitCode> {
    let spec = PerturbSpec::parse(&args.perturb).context("--perturb")?;
    let camera = match &args.camera {
        Some(text) => Some(Intrinsics::parse(text).context("--camera")?),
        None => None,
    };
    let input = PerturbInput::detect(&args.input).context("--input")?;
    let given = [
        ("--camera", args.camera.is_some()),
        ("--rate", args.rate.is_some()),
        ("--depth-png", args.depth_png.is_some()),
    ];
    let given = given.iter().find(|(_, given)| *given).map(|(flag, _)| flag);
    let states_its_own = match input {
        PerturbInput::Euroc(_) => Some("a EuRoC dataset; its cameras and rates come from its calibration files and it has no depth"),
        PerturbInput::Bag(_) => Some("a ROS 2 bag; its camera comes from its CameraInfo, its rate from its stamps, and its depth keeps its encoding"),
        _ => None,
    };
    if let (Some(flag), Some(why)) = (given, states_its_own) {
        anyhow::bail!("{flag}: {} is {why}", args.input.display());
    }
    let what = match input {
        PerturbInput::Dataset(_) | PerturbInput::Euroc(_) | PerturbInput::Bag(_) => None,
        PerturbInput::ImageFolder(_) => Some("a folder of images"),
        PerturbInput::Image(_) => Some("one image"),
    };
    if let (Some(what), Some(_)) = (what, args.depth_png) {
        anyhow::bail!(
            "--depth-png: {} is {what}, not a dataset; only datasets have depth PNGs to encode",
            args.input.display()
        );
    }
    if args.bag_compression.is_some() && !matches!(input, PerturbInput::Bag(_)) {
        anyhow::bail!(
            "--bag-compression: {} is not a ROS 2 bag; only a bag's output has MCAP chunks",
            args.input.display()
        );
    }
    let seed = args.seed;
    let source = match input {
        PerturbInput::Dataset(input) => Source::Dataset {
            input,
            overrides: DatasetOverrides {
                camera,
                rate_hz: args.rate,
            },
            depth_png: args.depth_png.unwrap_or_default(),
            spec,
            seed,
        },
        PerturbInput::Euroc(input) => Source::Euroc { input, spec, seed },
        PerturbInput::Bag(input) => Source::Bag {
            input,
            compression: args.bag_compression.unwrap_or_default(),
            spec,
            seed,
        },
        PerturbInput::ImageFolder(dir) => Source::Images {
            files: image_files(&dir)?,
            spec,
            seed,
        },
        PerturbInput::Image(file) => Source::Image { file, spec, seed },
    };
    let job = Job {
        source,
        out: args.out,
        force: args.force,
        command: super::typed_command(),
    };
    make(&[job], args.adapter)?;
    Ok(ExitCode::SUCCESS)
}
