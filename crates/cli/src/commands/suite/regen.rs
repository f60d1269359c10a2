use std::path::PathBuf;
use std::process::ExitCode;

use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_suite::{regen, Suite};

use crate::suite_progress::SuiteBars;

#[derive(clap::Args)]
#[command(
    after_help = "Remakes the frames of one sequence (deleted by `suite bench --ephemeral`, or damaged) \
from the job its kept manifest records, which the suite's row must still define, and compares every \
remade file with the kept checksum list. Exit 0 when every byte is the same (then `rslam verify \
DIR/datasets/NAME` passes against that list). Bytes are reproducible for the same rslam version on the \
same adapter; made by another, regen names both, lists the files that differ, keeps the earlier list as \
DIR/datasets/NAME.earlier.b3sum and exits 1."
)]
pub struct RegenArgs {
    /// The suite folder (holding suite.toml).
    dir: PathBuf,
    /// The sequence (`<scene>__<setting>`).
    name: String,
    /// Use the GPU whose name contains this text (default: a real GPU if any, else lavapipe).
    #[arg(long)]
    adapter: Option<String>,
}

pub fn run(args: RegenArgs) -> anyhow::Result<ExitCode> {
    let suite = Suite::open(&args.dir)?;
    let ctx = GpuContext::new(&AdapterChoice {
        name_contains: args.adapter,
    })?;
    let bars = SuiteBars::new();
    let done = regen(&ctx, &suite, &args.name, &bars)?;
    bars.finish();
    if done.made_by != done.remade_by {
        eprintln!(
            "made by {}; remade by {}: another version or GPU may round floats differently",
            done.made_by, done.remade_by
        );
    }
    let problems = done.problems();
    if problems.is_empty() {
        println!(
            "{}: {} files remade, every one equal to the kept checksums",
            done.dir.display(),
            done.files
        );
        return Ok(ExitCode::SUCCESS);
    }
    for line in problems.iter().take(20) {
        eprintln!("{}/{line}", done.dir.display());
    }
    if problems.len() > 20 {
        eprintln!("… and {} more", problems.len() - 20);
    }
    if let Some(earlier) = &done.earlier_list {
        eprintln!(
            "{} of {} files differ from the kept list, kept as {}",
            problems.len(),
            done.files,
            earlier.display()
        );
    }
    Ok(ExitCode::from(1))
}
