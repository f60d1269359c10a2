use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use indicatif::{ProgressBar, ProgressStyle};
use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_suite::bench::{
    bench_ephemeral, bench_suite, BenchOptions, BenchProgress, EphemeralOptions, Method, RunId,
    RunRecord,
};
use rslam_suite::{format_bytes, Suite};

use super::shard_args::ShardArgs;

use crate::interrupt::interrupt_flag;
use crate::suite_progress::{run_line, SuiteBars};

#[derive(clap::Args)]
#[command(
    after_help = "Each run writes into DIR/runs/<method>/<sequence>/: <repeat>.txt (the TUM estimate) when \
the method exits 0 with a readable estimate, else <repeat>.failed (the reason: exit status, signal, \
timeout, no or unreadable estimate), plus <repeat>.log (stdout and stderr), <repeat>.json (command, \
exit code, wall time, peak memory) and <repeat>.mesh.ply when the method writes a reconstruction. \
`rslam eval --runs DIR/runs --datasets DIR/datasets` and `rslam suite report DIR` read exactly this, \
a .failed run counting as a failure. A run with a .json is finished and never run again \
(--retry-failed runs the failed ones again). See examples/methods/ for method files.

--ephemeral keeps no frames: each sequence of the shard is made (on the GPU), run by every method and \
repeat still to run, then its frames are deleted; datasets/<name>/ keeps its manifest, checksum list \
and ground truth, which is all `suite report` and `eval --runs` read, and `rslam suite regen DIR NAME` \
remakes its frames exactly. --jobs is then the number of sequences in flight, each running its \
methods one after another: at most --jobs frame sets on disk and --jobs methods at once."
)]
pub struct BenchArgs {
    /// The suite folder; its sequences must be made (`rslam suite run`).
    dir: PathBuf,
    /// A method file (TOML), repeatable: name, reads, command, timeout_s, repeats, mesh.
    #[arg(long = "methods", required = true)]
    methods: Vec<PathBuf>,
    #[command(flatten)]
    shard: ShardArgs,
    /// Runs at once (with --ephemeral: sequences in flight, each running its methods in turn).
    #[arg(long, default_value_t = 1)]
    jobs: usize,
    /// Run the runs that failed before again.
    #[arg(long)]
    retry_failed: bool,
    /// Make each sequence, run it, then delete its frames (keeping manifest, checksums, ground
    /// truth): disk for --jobs sequences, not the suite.
    #[arg(long)]
    ephemeral: bool,
    /// With --ephemeral: make the frames in this node-local folder (default: $TMPDIR when set,
    /// else in place under DIR/datasets).
    #[arg(long, requires = "ephemeral", value_name = "DIR")]
    scratch: Option<PathBuf>,
    /// With --ephemeral: use the GPU whose name contains this text.
    #[arg(long, requires = "ephemeral")]
    adapter: Option<String>,
}

struct BenchBar {
    bar: ProgressBar,
    interrupted: Arc<AtomicBool>,
}

impl BenchProgress for BenchBar {
    fn begin(&self, runs: usize) {
        self.bar.set_length(runs as u64);
    }

    fn run_done(&self, run: &RunId, record: &RunRecord) {
        let line = run_line(run, record);
        if self.bar.is_hidden() {
            eprintln!("{line}");
        } else {
            self.bar.println(line);
        }
        self.bar.inc(1);
    }

    fn interrupted(&self) -> &AtomicBool {
        &self.interrupted
    }
}

pub fn run(args: BenchArgs) -> anyhow::Result<ExitCode> {
    let suite = Suite::open(&args.dir)?;
    let methods = args
        .methods
        .iter()
        .map(|path| Method::read(path))
        .collect::<Result<Vec<_>, _>>()?;
    let (shard, _) = args.shard.resolve()?;
    let options = BenchOptions {
        shard,
        jobs: args.jobs.max(1),
        retry_failed: args.retry_failed,
    };
    if args.ephemeral {
        return run_ephemeral(&args, &suite, &methods, options);
    }
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("bench [{bar:40}] {pos}/{len} runs, eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let progress = BenchBar {
        bar,
        interrupted: interrupt_flag(),
    };
    let summary = bench_suite(&suite, &methods, options, &progress)?;
    progress.bar.finish_and_clear();
    eprintln!(
        "shard {shard}: {} runs succeeded, {} failed now; {} were done before",
        summary.succeeded,
        summary.failed.len(),
        summary.already_done
    );
    if !summary.sequences_not_made.is_empty() {
        eprintln!(
            "{} sequence(s) not made yet, not run (rslam suite run {} first): {}",
            summary.sequences_not_made.len(),
            args.dir.display(),
            summary.sequences_not_made.join(", ")
        );
    }
    if !summary.sequences_frames_deleted.is_empty() {
        eprintln!(
            "{} sequence(s) had their frames deleted after their runs, not run (--ephemeral makes them again for the runs left): {}",
            summary.sequences_frames_deleted.len(),
            summary.sequences_frames_deleted.join(", ")
        );
    }
    eprintln!("report: rslam suite report {}", args.dir.display());
    Ok(ExitCode::SUCCESS)
}

fn run_ephemeral(
    args: &BenchArgs,
    suite: &Suite,
    methods: &[Method],
    bench: BenchOptions,
) -> anyhow::Result<ExitCode> {
    let scratch = args
        .scratch
        .clone()
        .or_else(|| std::env::var_os("TMPDIR").map(PathBuf::from));
    let ctx = GpuContext::new(&AdapterChoice {
        name_contains: args.adapter.clone(),
    })?;
    let bars = SuiteBars::new();
    bars.line(&format!("adapter: {}", ctx.describe()));
    bars.line(&format!(
        "shard {}: {} sequence(s) in flight, frames made in {}",
        bench.shard,
        bench.jobs,
        scratch
            .as_ref()
            .map_or("place (DIR/datasets)".into(), |s| s.display().to_string())
    ));
    let options = EphemeralOptions { bench, scratch };
    let summary = bench_ephemeral(&ctx, suite, methods, &options, &bars, &bars)?;
    bars.finish();
    let deleted: u64 = summary.used.iter().map(|(_, d)| d.bytes).sum();
    eprintln!(
        "shard {}: {} sequence(s) used now ({} of frames deleted), {} before; {} runs succeeded, {} failed now; {} were done before",
        bench.shard,
        summary.used.len(),
        format_bytes(deleted),
        summary.sequences_done_before,
        summary.runs_succeeded,
        summary.runs_failed.len(),
        summary.runs_done_before
    );
    for name in &summary.busy {
        eprintln!("left to another process: {name}");
    }
    for (name, why) in &summary.conflicts {
        eprintln!("left alone: {name}: {why} (`rslam suite run --force` remakes it)");
    }
    for (name, why) in &summary.failed {
        eprintln!("failed: {name}: {why}");
    }
    eprintln!("report: rslam suite report {}", args.dir.display());
    Ok(
        if summary.conflicts.is_empty() && summary.failed.is_empty() {
            ExitCode::SUCCESS
        } else {
            ExitCode::from(1)
        },
    )
}
