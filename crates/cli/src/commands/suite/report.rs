use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rslam_core::trajectory_io::ReadOptions;
use rslam_eval::recon::Culling;
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
    /// What of each surface the mapping metrics measure: none, frustum or visible (what the
    /// sequence's ground-truth cameras saw; see `rslam eval recon --help`).
    #[arg(long, default_value_t = Culling::default())]
    cull: Culling,
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
    let (reconstructions, recon_files) = report_reconstructions(&suite, &out, args.cull)?;
    if !reconstructions.is_empty() {
        println!(
            "\n{} reconstruction(s) against the ground-truth meshes, culling {} (cm, cm, %):",
            reconstructions.len(),
            args.cull
        );
        for r in &reconstructions {
            let what = match (&r.metrics, &r.failure) {
                (Some(m), _) => format!(
                    "accuracy {:.2}, completion {:.2}, ratio {:.1}",
                    m.accuracy_cm, m.completion_cm, m.completion_ratio_percent
                ),
                (None, failure) => {
                    format!("not measured: {}", failure.as_deref().unwrap_or_default())
                }
            };
            println!("{} {} #{}: {what}", r.method, r.sequence, r.repeat);
        }
    }
    println!("\nwritten:");
    for path in written.iter().chain(&recon_files) {
        println!("  {}", path.display());
    }
    Ok(ExitCode::SUCCESS)
}
