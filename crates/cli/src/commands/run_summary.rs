//! The line a generating command ends with.

use std::path::Path;

use rslam_pipeline::{FolderState, RunReport};

use crate::progress_bar::ProgressBar;

pub fn print_summary(report: &RunReport, out: &Path, progress: &ProgressBar) {
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
            "resumed {out}: {} source frames made now{rate}, the rest kept; {} frames",
            report.made, report.frames
        ),
        FolderState::Fresh => eprintln!("wrote {} frames to {out}{rate}", report.frames),
    }
}
