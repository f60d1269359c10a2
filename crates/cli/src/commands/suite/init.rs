use std::path::PathBuf;
use std::process::ExitCode;

use rslam_core::dataset::{DatasetFormat, DepthPng};
use rslam_suite::{write_suite, InitOptions, Preset};

#[derive(clap::Args)]
pub struct InitArgs {
    /// robust-slam: docs/src/perturbations.md §7, 125 settings × 8 scenes; mini: 7 settings on room0, 200 frames.
    #[arg(long, default_value = "robust-slam")]
    preset: Preset,
    /// The suite folder to create (suite.toml goes there; datasets/ later).
    #[arg(long)]
    out: PathBuf,
    /// Only these scenes, comma-separated (e.g. room0,office2).
    #[arg(long, value_delimiter = ',')]
    scenes: Option<Vec<String>>,
    /// Frames per sequence (the first N poses of each path); default: the preset's.
    #[arg(long)]
    frames: Option<usize>,
    /// Dataset layout of every sequence, with its camera: replica (1200x680), tum (640x480) or
    /// ros2 (a ROS 2 bag of the replica camera).
    #[arg(long, default_value = "replica")]
    format: DatasetFormat,
    /// Depth PNG compression: fast, or small (lossless, about 40 % smaller datasets on clean
    /// depth, more CPU per frame; see docs/src/formats.md, "Depth PNGs").
    #[arg(long, default_value = "fast")]
    depth_png: DepthPng,
    /// Suite seed; each sequence's seed is derived from it and the sequence's name.
    #[arg(long, default_value_t = 0)]
    seed: u64,
}

pub fn run(args: InitArgs) -> anyhow::Result<ExitCode> {
    let options = InitOptions {
        preset: args.preset,
        scenes: args.scenes,
        frames: args.frames,
        format: args.format,
        depth_png: args.depth_png,
        seed: args.seed,
    };
    let (path, suite) = write_suite(&args.out, &options)?;
    println!(
        "wrote {}: {} sequences",
        path.display(),
        suite.sequences.len()
    );
    eprintln!(
        "next: rslam suite status {} --plan; rslam suite run {}",
        args.out.display(),
        args.out.display()
    );
    Ok(ExitCode::SUCCESS)
}
