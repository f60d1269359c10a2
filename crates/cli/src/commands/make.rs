//! Making jobs from the command line: each planned, then run, with the GPU opened once the first
//! job's plan stands, so that a job its plan refuses fails before any GPU work.

use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_pipeline::Job;

use super::run_summary::print_summary;
use crate::progress_bar::ProgressBar;

/// Plans and runs `jobs` in order on the GPU whose name contains `adapter` (default: a real GPU
/// if any, else lavapipe), printing what each wrote.
pub fn make(jobs: &[Job], adapter: Option<String>) -> anyhow::Result<()> {
    let progress = ProgressBar::new();
    let mut gpu: Option<GpuContext> = None;
    for job in jobs {
        let planned = job.plan()?;
        let ctx = match &mut gpu {
            Some(ctx) => ctx,
            None => {
                let ctx = GpuContext::new(&AdapterChoice {
                    name_contains: adapter.clone(),
                })?;
                eprintln!("adapter: {}", ctx.describe());
                gpu.insert(ctx)
            }
        };
        let report = planned.run(ctx, &progress)?;
        print_summary(&report, &job.out, &progress)?;
    }
    Ok(())
}
