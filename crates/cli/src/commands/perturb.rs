use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rslam_gpu::AdapterChoice;
use rslam_perturb::PerturbSpec;

use crate::generate::{run_perturb, PerturbInput, PerturbJob};

#[derive(clap::Args)]
pub struct PerturbArgs {
    /// A dataset (Replica or TUM layout), a folder of PNG/JPEG images, or one image.
    #[arg(long)]
    input: PathBuf,
    /// Output: a folder for datasets and image folders, a file for one image (same format).
    #[arg(long)]
    out: PathBuf,
    /// Perturbations, e.g. `gaussian_noise:3,depth_missing:5,misalign:10` (see `rslam list`).
    #[arg(long)]
    perturb: String,
    /// Seed of every random draw.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Use the GPU whose name contains this text (default: a real GPU if any, else lavapipe).
    #[arg(long)]
    adapter: Option<String>,
}

pub fn run(args: PerturbArgs) -> anyhow::Result<ExitCode> {
    let perturb = PerturbSpec::parse(&args.perturb).context("--perturb")?;
    let job = PerturbJob {
        input: PerturbInput::detect(&args.input)?,
        out: args.out,
        perturb,
        seed: args.seed,
        adapter: AdapterChoice {
            name_contains: args.adapter,
        },
        command: std::env::args().collect(),
    };
    let out = job.out.clone();
    let count = run_perturb(job)?;
    eprintln!("wrote {count} perturbed frames to {}", out.display());
    Ok(ExitCode::SUCCESS)
}
