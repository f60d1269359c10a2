//! The line a generating command ends with.

use std::path::Path;

use anyhow::Context;
use rslam_core::dataset::DatasetFormat;
use rslam_pipeline::rig::CameraFrames;
use rslam_pipeline::{FolderState, JobReport, Streams};
use rslam_suite::{folder_bytes, format_bytes};

use crate::progress_bar::ProgressBar;

pub fn print_summary(report: &JobReport, out: &Path, progress: &ProgressBar) -> anyhow::Result<()> {
    match (&report.streams, &report.manifest) {
        (_, None) => {
            eprintln!("wrote {}", out.display());
            Ok(())
        }
        (Streams::Frames(frames), Some(_)) => print_frames(*frames, report, out, progress),
        (
            Streams::Rig {
                cameras,
                imu_samples,
            },
            Some(_),
        ) => print_rig(cameras, *imu_samples, report, out, progress),
    }
}

/// The line of one camera's dataset or a folder of images: frames, size, where.
fn print_frames(
    frames: usize,
    report: &JobReport,
    out: &Path,
    progress: &ProgressBar,
) -> anyhow::Result<()> {
    let bytes = folder_bytes(out).with_context(|| format!("size of {}", out.display()))?;
    let size = format!(
        "{} per frame, {} in all",
        format_bytes(bytes / frames.max(1) as u64),
        format_bytes(bytes)
    );
    let out = out.display();
    let rate = progress
        .rate()
        .map(|fps| format!(" ({fps:.1} frames/s)"))
        .unwrap_or_default();
    match report.found {
        FolderState::Complete => eprintln!(
            "{out} is already complete ({frames} frames, same job); nothing to do (--force redoes it)"
        ),
        FolderState::Resume => eprintln!(
            "resumed {out}: {} source frames made now{rate}, the rest kept; {frames} frames, {size}",
            report.made
        ),
        FolderState::Fresh => eprintln!("wrote {frames} frames to {out}{rate}: {size}"),
    }
    Ok(())
}

/// The line of a rig's dataset: frames per camera, IMU samples, where.
fn print_rig(
    cameras: &[CameraFrames],
    imu_samples: usize,
    report: &JobReport,
    out: &Path,
    progress: &ProgressBar,
) -> anyhow::Result<()> {
    let bytes = folder_bytes(out).with_context(|| format!("size of {}", out.display()))?;
    let mut streams: Vec<String> = cameras
        .iter()
        .map(|c| format!("{} frames from {}", c.frames, c.name))
        .collect();
    if imu_samples > 0 {
        streams.push(format!("{imu_samples} IMU samples"));
    }
    let streams = streams.join(", ");
    let out = out.display();
    let rate = progress
        .rate()
        .map(|fps| format!(" ({fps:.1} frames/s)"))
        .unwrap_or_default();
    let size = format_bytes(bytes);
    let layout = match report.manifest.as_ref().and_then(|m| m.format) {
        Some(DatasetFormat::Ros2) => "as a ROS 2 bag",
        _ => "in the EuRoC layout",
    };
    match report.found {
        FolderState::Complete => eprintln!(
            "{out} is already complete ({streams}, same job); nothing to do (--force redoes it)"
        ),
        FolderState::Resume if report.made == cameras.iter().map(|c| c.frames).sum::<usize>() => {
            eprintln!("started {out} over: wrote {streams} {layout}{rate}: {size}")
        }
        FolderState::Resume => eprintln!(
            "resumed {out}: {} frames made now{rate}, the rest kept; {streams} {layout}: {size}",
            report.made
        ),
        FolderState::Fresh => {
            eprintln!("wrote {streams} to {out} {layout}{rate}: {size}")
        }
    }
    Ok(())
}
