use std::fmt;
use std::path::PathBuf;
use std::str::FromStr;

use crate::Trajectory;

/// The trajectory file formats rslam reads (and, for TUM and Replica, writes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TrajectoryFormat {
    /// `t tx ty tz qx qy qz qw` per line, `#` comments.
    Tum,
    /// Replica `traj.txt`: 16 numbers per line, row-major 4×4 camera-to-world, no timestamps.
    Replica,
    /// KITTI odometry poses: 12 numbers per line, row-major 3×4, no timestamps.
    Kitti,
    /// EuRoC ground truth `data.csv`: `t[ns],px,py,pz,qw,qx,qy,qz,…`, `#` header.
    Euroc,
    /// COLMAP `images.txt`: world-to-camera per image, in name order, no timestamps.
    Colmap,
    /// A pose or TF topic of a ROS 2 bag (a rosbag2 folder, [`ReadOptions::topic`]).
    Ros2,
    /// nerfstudio JSON: a `camera_path.json` or a dataset's `transforms.json` (OpenGL camera
    /// axes, converted), the latter moved by [`ReadOptions::dataparser_transforms`].
    Nerfstudio,
}

impl TrajectoryFormat {
    pub const ALL: [TrajectoryFormat; 7] = [
        Self::Tum,
        Self::Replica,
        Self::Kitti,
        Self::Euroc,
        Self::Colmap,
        Self::Ros2,
        Self::Nerfstudio,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Self::Tum => "tum",
            Self::Replica => "replica",
            Self::Kitti => "kitti",
            Self::Euroc => "euroc",
            Self::Colmap => "colmap",
            Self::Ros2 => "ros2",
            Self::Nerfstudio => "nerfstudio",
        }
    }

    /// What one line holds, for error messages.
    pub fn line_layout(self) -> &'static str {
        match self {
            Self::Tum => "8 numbers 't tx ty tz qx qy qz qw'",
            Self::Replica => "16 numbers (row-major 4x4 camera-to-world)",
            Self::Kitti => "12 numbers (row-major 3x4 camera-to-world)",
            Self::Euroc => "at least 8 comma-separated numbers 't[ns],px,py,pz,qw,qx,qy,qz'",
            Self::Colmap => "an image line 'IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME' (world-to-camera), then its points line",
            Self::Ros2 => "a message of a pose topic",
            Self::Nerfstudio => "a camera_path.json or transforms.json of nerfstudio",
        }
    }
}

impl fmt::Display for TrajectoryFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The text is not one of the format names.
#[derive(Debug, thiserror::Error)]
#[error("unknown trajectory format '{text}': expected tum, replica, kitti, euroc, colmap, ros2 or nerfstudio")]
pub struct UnknownFormat {
    pub text: String,
}

impl FromStr for TrajectoryFormat {
    type Err = UnknownFormat;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|f| f.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| UnknownFormat {
                text: s.to_string(),
            })
    }
}

/// Where the timestamps of a read trajectory come from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TimeSource {
    /// Read from the file (TUM, EuRoC) or from a KITTI times file.
    File,
    /// Synthesised as `i / hz` (Replica `traj.txt`, COLMAP `images.txt`, a nerfstudio camera
    /// path at its `fps`).
    Rate { hz: f64 },
    /// No time at all (KITTI without a times file): the timestamps hold the frame index
    /// `0, 1, 2, …`, and such a trajectory is matched to another by index.
    FrameIndex,
}

/// How to read a trajectory file. `Default` auto-detects the format and stamps Replica frames at
/// 20 Hz.
#[derive(Clone, Debug, PartialEq)]
pub struct ReadOptions {
    /// Force a format instead of detecting it from the content.
    pub format: Option<TrajectoryFormat>,
    /// Frame rate giving Replica frame `i` (and COLMAP image `i` in name order) the timestamp
    /// `i / replica_rate_hz`.
    pub replica_rate_hz: f64,
    /// KITTI times file (one timestamp in seconds per line, as `times.txt` of KITTI odometry).
    pub kitti_times: Option<PathBuf>,
    /// The topic of a ROS 2 bag to read: `TOPIC`, or `TOPIC:CHILD` for a TF topic's transforms
    /// to frame `CHILD`; `None` for the bag's one pose topic.
    pub topic: Option<String>,
    /// nerfstudio's `dataparser_transforms.json`, which moves a `transforms.json`'s cameras into
    /// the frame of the model trained on them (and of its exported splats).
    pub dataparser_transforms: Option<PathBuf>,
}

impl ReadOptions {
    pub const DEFAULT_REPLICA_RATE_HZ: f64 = crate::REPLICA_RATE_HZ;
}

impl Default for ReadOptions {
    fn default() -> Self {
        Self {
            format: None,
            replica_rate_hz: Self::DEFAULT_REPLICA_RATE_HZ,
            kitti_times: None,
            topic: None,
            dataparser_transforms: None,
        }
    }
}

/// A trajectory as read from a file, with what was known about it.
#[derive(Clone, Debug, PartialEq)]
pub struct TrajectoryFile {
    pub format: TrajectoryFormat,
    pub time_source: TimeSource,
    pub trajectory: Trajectory,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_names_parse_back_case_insensitively() {
        for f in TrajectoryFormat::ALL {
            assert_eq!(f.name().parse::<TrajectoryFormat>().unwrap(), f);
            assert_eq!(
                f.name().to_uppercase().parse::<TrajectoryFormat>().unwrap(),
                f
            );
        }
        let err = "csv".parse::<TrajectoryFormat>().unwrap_err();
        assert_eq!(
            err.to_string(),
            "unknown trajectory format 'csv': expected tum, replica, kitti, euroc, colmap, ros2 or nerfstudio"
        );
    }
}
