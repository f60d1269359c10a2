//! The line a generating command ends with.

use std::path::Path;

use anyhow::Context;
use rslam_pipeline::{FolderState, RigReport, RunReport};
use rslam_suite::{folder_bytes, format_bytes};

use crate::progress_bar::ProgressBar;

pub fn print_summary(report: &RunReport, out: &Path, progress: &ProgressBar) -> anyhow::Result<()> {
    let bytes = folder_bytes(out).with_context(|| format!("size of {}", out.display()))?;
    let size = format!(
        "{} per frame, {} in all",
        format_bytes(bytes / report.frames.max(1) as u64),
        format_bytes(bytes)
    );
    let out = out.display();
    let rate = progress
        .rate()
        .map(|fps| format!(" ({fps:.1} frames/s)"))
        .unwrap_or_default();
    match report.found {
        FolderState::Complete => eprintln!(
            "{out} is already complete ({} frames, same job); nothing to do (--force redoes it)",
            report.frames
        ),
        FolderState::Resume => eprintln!(
            "resumed {out}: {} source frames made now{rate}, the rest kept; {} frames, {size}",
            report.made, report.frames
        ),
        FolderState::Fresh => eprintln!("wrote {} frames to {out}{rate}: {size}", report.frames),
    }
    Ok(())
}

/// The line a rig render ends with: frames per camera, IMU samples, where.
pub fn print_rig_summary(
    report: &RigReport,
    out: &Path,
    progress: &ProgressBar,
) -> anyhow::Result<()> {
    let bytes = folder_bytes(out).with_context(|| format!("size of {}", out.display()))?;
    let mut streams: Vec<String> = report
        .cameras
        .iter()
        .map(|c| format!("{} frames from {}", c.frames, c.name))
        .collect();
    if report.imu_samples > 0 {
        streams.push(format!("{} IMU samples", report.imu_samples));
    }
    let streams = streams.join(", ");
    let out = out.display();
    let rate = progress
        .rate()
        .map(|fps| format!(" ({fps:.1} frames/s)"))
        .unwrap_or_default();
    let size = format_bytes(bytes);
    match report.found {
        FolderState::Complete => eprintln!(
            "{out} is already complete ({streams}, same job); nothing to do (--force redoes it)"
        ),
        FolderState::Resume if report.made == report.cameras.iter().map(|c| c.frames).sum::<usize>() => {
            eprintln!("started {out} over: wrote {streams} in the EuRoC layout{rate}: {size}")
        }
        FolderState::Resume => eprintln!(
            "resumed {out}: {} frames made now{rate}, the rest kept; {streams} in the EuRoC layout: {size}",
            report.made
        ),
        FolderState::Fresh => {
            eprintln!("wrote {streams} to {out} in the EuRoC layout{rate}: {size}")
        }
    }
    Ok(())
}
