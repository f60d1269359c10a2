use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rslam_core::trajectory_io::ReadOptions;
use rslam_eval::recon::Culling;
use rslam_eval::runs::{evaluate_runs_into, summary_text, RunsOptions, DEFAULT_FAILURE_ATE};
use rslam_eval::EvalOptions;
use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_suite::bench::{
    ate_correlations, report_reconstructions, report_rendered_views, RUNS_DIR,
};
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
    /// For the clean frames that rendered views are compared with: use the GPU whose name
    /// contains this text (default: a real GPU if any, else lavapipe).
    #[arg(long)]
    adapter: Option<String>,
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
            let measures = r.metrics.as_ref().map(|m| {
                format!(
                    "accuracy {:.2}, completion {:.2}, ratio {:.1}",
                    m.accuracy_cm, m.completion_cm, m.completion_ratio_percent
                )
            });
            let what = measures_or_failure(measures, r.failure.as_deref());
            println!("{} {} #{}: {what}", r.method, r.sequence, r.repeat);
        }
    }
    let ate_of = |method: &str, sequence: &str, repeat: usize| {
        let repeat = repeat.to_string();
        report
            .runs
            .iter()
            .find(|r| {
                r.method == method && r.sequence == sequence && r.repeat.as_deref() == Some(&repeat)
            })
            .filter(|r| !r.failed())
            .map(|r| r.ate)
    };
    let gpu = || {
        let choice = AdapterChoice {
            name_contains: args.adapter.clone(),
        };
        GpuContext::new(&choice).map_err(|e| rslam_pipeline::PipelineError::from(e).into())
    };
    let (views, view_files) = report_rendered_views(&suite, &out, gpu, &ate_of)?;
    if !views.is_empty() {
        println!(
            "\n{} run(s) rendered their map at the ground-truth poses (against the clean frames):",
            views.len()
        );
        let number = |v: Option<f64>, decimals: usize| {
            v.map_or("-".to_string(), |v| format!("{v:.decimals$}"))
        };
        for r in &views {
            let measures = r.quality.as_ref().map(|q| {
                format!(
                    "PSNR {} dB, SSIM {} over {} frame(s); depth L1 {} cm over {}",
                    number(q.psnr_db, 2),
                    number(q.ssim, 4),
                    q.colour_frames,
                    number(q.depth_l1_cm, 2),
                    q.depth_frames
                )
            });
            let what = measures_or_failure(measures, r.failure.as_deref());
            println!("{} {} #{}: {what}", r.method, r.sequence, r.repeat);
        }
        for c in ate_correlations(&views) {
            println!(
                "{} against ATE over {} run(s): Spearman {}, Pearson {}",
                c.measure,
                c.runs,
                number(c.spearman, 3),
                number(c.pearson, 3)
            );
        }
    }
    println!("\nwritten:");
    for path in written.iter().chain(&recon_files).chain(&view_files) {
        println!("  {}", path.display());
    }
    Ok(ExitCode::SUCCESS)
}

/// A run's measures as printed, or why it was not measured.
fn measures_or_failure(measures: Option<String>, failure: Option<&str>) -> String {
    measures.unwrap_or_else(|| format!("not measured: {}", failure.unwrap_or_default()))
}
