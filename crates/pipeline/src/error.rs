use std::fmt;
use std::path::PathBuf;

use rslam_core::dataset::Layout;
use rslam_core::CoreError;
use rslam_gpu::GpuError;
use rslam_perturb::PerturbError;
use rslam_render::RenderError;

/// Errors of a generation run; each names the file, option or frame that was wrong.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    #[error(transparent)]
    Core(#[from] CoreError),
    #[error(transparent)]
    Gpu(#[from] GpuError),
    #[error(transparent)]
    Perturb(#[from] PerturbError),
    #[error(transparent)]
    Render(#[from] RenderError),
    /// A part of a job that cannot work as given.
    #[error("{part}: {message}")]
    Option { part: JobPart, message: String },
    /// A rig (a preset's or a rig file's name) written in a layout that cannot hold it.
    #[error("{}", rig_in_layout(rig, *layout))]
    RigLayout { rig: String, layout: Layout },
    /// An input file or folder that cannot be used as it is.
    #[error("{}: {message}", path.display())]
    Input { path: PathBuf, message: String },
    /// An output folder that this run may not write into.
    #[error("{}: {message}", path.display())]
    Output { path: PathBuf, message: String },
    /// An output folder that holds (part of) another job's output (`holds` says what and how it
    /// differs); forcing the run starts over.
    #[error("{}: holds {holds}; choose another output or force a fresh start", path.display())]
    OtherJob { path: PathBuf, holds: String },
    #[error(
        "interrupted: the output is incomplete (no rslam.json written); run the same command again to resume"
    )]
    Interrupted,
    #[error("an encoder thread stopped: {0}")]
    Worker(String),
}

/// The part of a job an error is about, in the library's words (its `Display`); the CLI and
/// Python name each by their own flag or argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JobPart {
    /// The perturbation spec.
    Spec,
    /// How many poses of the camera path are drawn, or the frames given in memory.
    Frames,
    /// One frame, by its index.
    Frame,
    /// The indices of frames given in memory.
    FrameIndices,
    /// The rate of the path's poses.
    Rate,
    /// The camera: its intrinsics and image size.
    Camera,
    /// The rig of sensors.
    Rig,
    /// The camera path file.
    Trajectory,
    /// Camera poses given in memory.
    Poses,
    /// How many agents share the scene.
    Agents,
    /// How a ROS 2 bag is written (its depth encoding, `/tf`, compression).
    Bag,
    /// A Gaussian-splat capture's metric scale.
    CaptureScale,
    /// The accumulated opacity under which a capture's pixel has no depth.
    CaptureOpacity,
    /// A user's actor: its mesh and path files.
    Actor,
}

impl fmt::Display for JobPart {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Spec => "spec",
            Self::Frames => "frames",
            Self::Frame => "frame",
            Self::FrameIndices => "frame_indices",
            Self::Rate => "rate",
            Self::Camera => "camera",
            Self::Rig => "rig",
            Self::Trajectory => "trajectory",
            Self::Poses => "poses",
            Self::Agents => "agents",
            Self::Bag => "bag options",
            Self::CaptureScale => "capture scale",
            Self::CaptureOpacity => "capture min opacity",
            Self::Actor => "actor",
        })
    }
}

/// Why `rig` cannot be written in `layout`, and which layout (or rigs) it takes.
fn rig_in_layout(rig: &str, layout: Layout) -> String {
    match (rig, layout) {
        (_, Layout::Euroc) => format!(
            "layout euroc: holds a rig of several sensors (stereo, stereo-imu or a rig file), not '{rig}'"
        ),
        ("rgbd-imu", _) => {
            format!("rig 'rgbd-imu': needs the tum layout (with imu0/ beside it), not {layout}")
        }
        _ => format!("rig '{rig}': a rig of several sensors needs the euroc layout, not {layout}"),
    }
}

impl PipelineError {
    pub fn option(part: JobPart, message: impl Into<String>) -> Self {
        Self::Option {
            part,
            message: message.into(),
        }
    }

    pub fn input(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        Self::Input {
            path: path.into(),
            message: message.into(),
        }
    }

    pub fn output(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        Self::Output {
            path: path.into(),
            message: message.into(),
        }
    }
}
