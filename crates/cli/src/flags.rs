//! Library errors name the part of a job (`spec`, `frames`, `rig`) and the spec item in the
//! library's words; `rslam` says which flag sets it.

use std::error::Error;

use rslam_core::dataset::Layout;
use rslam_perturb::PerturbError;
use rslam_pipeline::{JobPart, PipelineError};
use rslam_suite::SuiteError;

/// The flag that sets `part` (parts the command line never sets keep the library's word).
fn flag(part: JobPart) -> String {
    match part {
        JobPart::Spec => "--perturb".into(),
        JobPart::Frames => "--frames".into(),
        JobPart::Rate => "--rate".into(),
        JobPart::Camera => "--camera".into(),
        JobPart::Rig => "--rig".into(),
        JobPart::Trajectory => "--traj".into(),
        JobPart::Agents => "--agents".into(),
        JobPart::Bag => "--bag-depth/--bag-tf/--bag-compression".into(),
        JobPart::CaptureScale => "--capture-scale".into(),
        JobPart::CaptureOpacity => "--capture-min-opacity".into(),
        JobPart::Actor => "--actor".into(),
        JobPart::Frame | JobPart::FrameIndices | JobPart::Poses => part.to_string(),
    }
}

/// A rig given with a layout that cannot hold it, as the flags that fix it.
fn rig_in_layout(rig: &str, layout: Layout) -> String {
    match (rig, layout) {
        (_, Layout::Euroc) => "--format euroc: needs --rig stereo|stereo-imu|FILE.toml (the EuRoC layout is for those rigs)".into(),
        ("rgbd-imu", _) => {
            "--rig rgbd-imu: needs --format tum (the TUM layout with imu0/ beside it) or ros2 (a bag with /imu0)".into()
        }
        _ => format!("--rig {rig}: needs --format euroc or ros2 (the stereo rigs and rig files are written in the EuRoC layout or as a ROS 2 bag)"),
    }
}

/// The error as `rslam` prints it: its chain joined by `: `, each link that names a part of a
/// job or a spec item naming the flag instead. A link that the one before already ends with is
/// left out: the libraries' file errors print their I/O cause ("{path}: {source}") and keep it as
/// their source as well.
pub fn worded(error: &anyhow::Error) -> String {
    let mut links: Vec<String> = Vec::new();
    for text in error.chain().map(link) {
        if !links.last().is_some_and(|before| before.ends_with(&text)) {
            links.push(text);
        }
    }
    links.join(": ")
}

fn link(error: &(dyn Error + 'static)) -> String {
    let pipeline = error.downcast_ref::<PipelineError>().or_else(|| {
        match error.downcast_ref::<SuiteError>() {
            Some(SuiteError::Pipeline(inner)) => Some(inner),
            _ => None,
        }
    });
    let perturb = match pipeline {
        Some(PipelineError::Perturb(inner)) => Some(inner),
        _ => error.downcast_ref::<PerturbError>(),
    };
    match (pipeline, perturb) {
        (Some(PipelineError::Option { part, message }), _) => format!("{}: {message}", flag(*part)),
        (Some(PipelineError::RigLayout { rig, layout }), _) => rig_in_layout(rig, *layout),
        (Some(PipelineError::OtherJob { path, holds }), _) => format!(
            "{}: holds {holds}; choose another output or pass --force to start over",
            path.display()
        ),
        (_, Some(PerturbError::Spec { item, message })) => {
            format!("--perturb item '{item}': {message}")
        }
        _ => error.to_string(),
    }
}
