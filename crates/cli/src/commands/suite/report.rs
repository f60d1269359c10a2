use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rslam_core::trajectory_io::ReadOptions;
use rslam_eval::runs::{evaluate_runs_into, summary_text, RunsOptions, DEFAULT_FAILURE_ATE};
use rslam_eval::EvalOptions;
use rslam_suite::bench::{report_reconstructions, RUNS_DIR};
use rslam_suite::{Suite, DATASETS_DIR};

#[derive(clap::Args)]
pub struct ReportArgs {
    /// The suite folder, after `rslam suite bench`.
    dir: PathBuf,
    /// Where the report goes; default: DIR/report.
    #[arg(long)]
    out: Option<PathBuf>,
    /// ATE counted for a failed run, metres.
    #[arg(long, default_value_t = DEFAULT_FAILURE_ATE)]
    failure_ate: f64,
}

pub fn run(args: ReportArgs) -> anyhow::Result<ExitCode> {
    let suite = Suite::open(&args.dir)?;
    let out = args.out.unwrap_or_else(|| args.dir.join("report"));
    let options = RunsOptions {
        runs_dir: args.dir.join(RUNS_DIR),
        datasets_dir: args.dir.join(DATASETS_DIR),
        read: ReadOptions {
            replica_rate_hz: suite.replica_rate_hz()?,
            ..ReadOptions::default()
        },
        eval: EvalOptions::default(),
        failure_ate: args.failure_ate,
        skip_dir: None,
    };
    let (report, written) = evaluate_runs_into(&options, &out)
        .with_context(|| format!("evaluating the runs of {}", args.dir.display()))?;
    print!("{}", summary_text(&report));
    let (reconstructions, recon_files) = report_reconstructions(&suite, &out)?;
    if !reconstructions.is_empty() {
        println!(
            "\n{} reconstruction(s) against the ground-truth meshes (cm, cm, %):",
            reconstructions.len()
        );
        for r in &reconstructions {
            let m = &r.metrics;
            println!(
                "{} {} #{}: accuracy {:.2}, completion {:.2}, ratio {:.1}",
                r.method,
                r.sequence,
                r.repeat,
                m.accuracy_cm,
                m.completion_cm,
                m.completion_ratio_percent
            );
        }
    }
    println!("\nwritten:");
    for path in written.iter().chain(&recon_files) {
        println!("  {}", path.display());
    }
    Ok(ExitCode::SUCCESS)
}
