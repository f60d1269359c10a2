use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rslam_core::dataset::DatasetFormat;
use rslam_core::trajectory_io::ReadOptions;
use rslam_eval::runs::{evaluate_runs_into, summary_text, RunsOptions, DEFAULT_FAILURE_ATE};
use rslam_eval::EvalOptions;
use rslam_suite::bench::{evaluate_reconstructions, reconstruction_csv, RUNS_DIR};
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
            replica_rate_hz: replica_rate(&suite)?,
            ..ReadOptions::default()
        },
        eval: EvalOptions::default(),
        failure_ate: args.failure_ate,
        skip_dir: None,
    };
    let (report, written) = evaluate_runs_into(&options, &out)
        .with_context(|| format!("evaluating the runs of {}", args.dir.display()))?;
    print!("{}", summary_text(&report));
    let reconstructions = evaluate_reconstructions(&suite, &out)?;
    let mut written = written;
    if !reconstructions.is_empty() {
        let csv = out.join("reconstruction.csv");
        std::fs::write(&csv, reconstruction_csv(&reconstructions))
            .with_context(|| csv.display().to_string())?;
        let json = out.join("reconstruction.json");
        std::fs::write(&json, serde_json::to_string_pretty(&reconstructions)?)
            .with_context(|| json.display().to_string())?;
        println!(
            "\n{} reconstruction(s) against the ground-truth meshes:",
            reconstructions.len()
        );
        print!("{}", reconstruction_csv(&reconstructions));
        written.extend([csv, json]);
    }
    println!("\nwritten:");
    for path in written {
        println!("  {}", path.display());
    }
    Ok(ExitCode::SUCCESS)
}

/// Replica-layout ground truth has no timestamps: its frames are stamped at the sequences' rate,
/// which must then be one rate for the whole suite.
fn replica_rate(suite: &Suite) -> anyhow::Result<f64> {
    let mut rates = suite
        .sequences
        .iter()
        .filter(|s| s.format == DatasetFormat::Replica)
        .map(|s| (s.rate_hz, &s.name));
    let Some((rate, first)) = rates.next() else {
        return Ok(ReadOptions::DEFAULT_REPLICA_RATE_HZ);
    };
    if let Some((other, name)) = rates.find(|(r, _)| *r != rate) {
        anyhow::bail!(
            "{}: Replica-layout sequences at {rate} Hz ({first}) and {other} Hz ({name}); a report reads one rate: make separate suites",
            suite.dir.join(rslam_suite::SUITE_FILE).display()
        );
    }
    Ok(rate)
}
