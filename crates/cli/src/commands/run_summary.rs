//! The line a generating command ends with.

use std::path::Path;

use anyhow::Context;
use rslam_pipeline::{FolderState, RunReport};
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
