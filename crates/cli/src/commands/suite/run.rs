use std::path::PathBuf;
use std::process::ExitCode;

use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_suite::{run_suite, RunOptions, ShardSource, Suite};

use super::shard_args::ShardArgs;

use crate::suite_progress::SuiteBars;

#[derive(clap::Args)]
pub struct RunArgs {
    /// The suite folder (holding suite.toml).
    dir: PathBuf,
    #[command(flatten)]
    shard: ShardArgs,
    /// Sequences made at once on the one GPU (more keeps a fast GPU busy while frames encode).
    #[arg(long, default_value_t = 1)]
    jobs: usize,
    /// Remake sequences in conflict with the suite (made from another definition, damaged).
    #[arg(long)]
    force: bool,
    /// Start even when the estimate says the file system cannot hold the rest.
    #[arg(long)]
    skip_space_check: bool,
    /// Use the GPU whose name contains this text (default: a real GPU if any, else lavapipe).
    #[arg(long)]
    adapter: Option<String>,
}

pub fn run(args: RunArgs) -> anyhow::Result<ExitCode> {
    let suite = Suite::open(&args.dir)?;
    let (shard, source) = args.shard.resolve()?;
    let ctx = GpuContext::new(&AdapterChoice {
        name_contains: args.adapter,
    })?;
    let bars = SuiteBars::new();
    let from = match source {
        ShardSource::Option => "--shard",
        ShardSource::Slurm => "Slurm array task",
        ShardSource::Kubernetes => "JOB_COMPLETION_INDEX",
        ShardSource::Whole => "whole suite",
    };
    bars.line(&format!("adapter: {}", ctx.describe()));
    bars.line(&format!(
        "shard {shard} ({from}), {} job(s) at once",
        args.jobs.max(1)
    ));
    let options = RunOptions {
        shard,
        jobs: args.jobs.max(1),
        force: args.force,
        check_space: !args.skip_space_check,
    };
    let summary = run_suite(&ctx, &suite, options, &bars)?;
    bars.finish();
    eprintln!(
        "shard {shard}: {} sequences; {} were complete, {} made now, {} left to another process",
        summary.in_shard,
        summary.already_complete,
        summary.made.len(),
        summary.busy.len()
    );
    if let Some(first) = summary.frames_deleted.first() {
        eprintln!(
            "left alone: {} sequence(s) whose frames were deleted after their runs (`rslam suite regen {} {first}` remakes one)",
            summary.frames_deleted.len(),
            args.dir.display()
        );
    }
    for (name, why) in &summary.conflicts {
        eprintln!("left alone: {name}: {why} (--force remakes it)");
    }
    for (name, why) in &summary.failed {
        eprintln!("failed: {name}: {why}");
    }
    let clean = summary.conflicts.is_empty() && summary.failed.is_empty();
    Ok(if clean {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
