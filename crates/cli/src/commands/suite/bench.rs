use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use indicatif::{ProgressBar, ProgressStyle};
use rslam_suite::bench::{bench_suite, BenchOptions, BenchProgress, Method, RunId, RunRecord};
use rslam_suite::Suite;

use super::shard_args::ShardArgs;

use crate::interrupt::interrupt_flag;

#[derive(clap::Args)]
#[command(
    after_help = "Each run writes into DIR/runs/<method>/<sequence>/: <repeat>.txt (the TUM estimate) when \
the method exits 0 with a readable estimate, else <repeat>.failed (the reason: exit status, signal, \
timeout, no or unreadable estimate), plus <repeat>.log (stdout and stderr), <repeat>.json (command, \
exit code, wall time, peak memory) and <repeat>.mesh.ply when the method writes a reconstruction. \
`rslam eval --runs DIR/runs --datasets DIR/datasets` and `rslam suite report DIR` read exactly this, \
a .failed run counting as a failure. A run with a .json is finished and never run again \
(--retry-failed runs the failed ones again). See examples/methods/ for method files."
)]
pub struct BenchArgs {
    /// The suite folder; its sequences must be made (`rslam suite run`).
    dir: PathBuf,
    /// A method file (TOML), repeatable: name, reads, command, timeout_s, repeats, mesh.
    #[arg(long = "methods", required = true)]
    methods: Vec<PathBuf>,
    #[command(flatten)]
    shard: ShardArgs,
    /// Runs at once.
    #[arg(long, default_value_t = 1)]
    jobs: usize,
    /// Run the runs that failed before again.
    #[arg(long)]
    retry_failed: bool,
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
        let outcome = match &record.failure {
            None => format!("ok in {:.1} s", record.seconds),
            Some(reason) => format!("F: {reason}"),
        };
        let line = format!("{} {} #{}: {outcome}", run.method, run.sequence, run.repeat);
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
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("bench [{bar:40}] {pos}/{len} runs, eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let progress = BenchBar {
        bar,
        interrupted: interrupt_flag(),
    };
    let options = BenchOptions {
        shard,
        jobs: args.jobs.max(1),
        retry_failed: args.retry_failed,
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
    eprintln!("report: rslam suite report {}", args.dir.display());
    Ok(ExitCode::SUCCESS)
}
