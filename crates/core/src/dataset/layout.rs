use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// The on-disk layout of a dataset of one RGB-D camera (docs/src/formats.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DatasetFormat {
    /// `results/frameNNNNNN.jpg`, `results/depthNNNNNN.png`, `traj.txt`, `cam_params.json`.
    Replica,
    /// `rgb/<t>.png`, `depth/<t>.png`, `rgb.txt`, `depth.txt`, `groundtruth.txt`, `associations.txt`.
    Tum,
    /// A rosbag2 folder: `<name>_0.mcap` and `metadata.yaml` ([`super::ros2`]).
    Ros2,
}

impl DatasetFormat {
    /// 16-bit depth units per metre (PNG files, or the bag's `16UC1` images).
    pub fn depth_scale(self) -> f64 {
        match self {
            Self::Replica => 6553.5,
            Self::Tum => 5000.0,
            Self::Ros2 => super::ros2::DEPTH_UNITS_PER_METRE,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Self::Replica => "replica",
            Self::Tum => "tum",
            Self::Ros2 => "ros2",
        }
    }
}

impl fmt::Display for DatasetFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for DatasetFormat {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "replica" => Ok(Self::Replica),
            "tum" => Ok(Self::Tum),
            "ros2" => Ok(Self::Ros2),
            _ => Err(format!(
                "unknown dataset format '{s}': expected replica, tum or ros2"
            )),
        }
    }
}

/// Every layout rslam writes a dataset in: the two of one RGB-D camera ([`DatasetFormat`]), and
/// EuRoC's for a rig of cameras and an IMU (docs/src/formats.md, "EuRoC (ASL) layout").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Layout {
    /// One RGB-D camera in a core layout (replica, tum).
    Camera(DatasetFormat),
    /// A rig's cameras and IMU in the EuRoC (ASL) layout.
    Euroc,
}

impl Layout {
    pub fn name(self) -> &'static str {
        match self {
            Self::Camera(format) => format.name(),
            Self::Euroc => "euroc",
        }
    }

    /// The file a method reads the camera from, in the dataset folder: the camera's parameters,
    /// or for a rig ORB-SLAM3's stereo settings (`orbslam3_stereo_inertial.yaml` lies beside it
    /// when the rig has an IMU).
    pub fn camera_file(self) -> &'static str {
        match self {
            Self::Camera(DatasetFormat::Replica) => "cam_params.json",
            Self::Camera(DatasetFormat::Tum) => "orbslam3.yaml",
            Self::Camera(DatasetFormat::Ros2) => "metadata.yaml",
            Self::Euroc => super::euroc::ORBSLAM3_STEREO_FILE,
        }
    }
}

impl fmt::Display for Layout {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Layout {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "euroc" => Ok(Self::Euroc),
            _ => s.parse().map(Self::Camera).map_err(|_| {
                format!("unknown dataset layout '{s}': expected replica, tum, ros2 or euroc")
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_read_back_and_each_layout_has_its_camera_file() {
        for layout in [
            Layout::Camera(DatasetFormat::Replica),
            Layout::Camera(DatasetFormat::Tum),
            Layout::Camera(DatasetFormat::Ros2),
            Layout::Euroc,
        ] {
            assert_eq!(layout.name().parse::<Layout>(), Ok(layout));
        }
        assert_eq!(Layout::Euroc.camera_file(), "orbslam3_stereo.yaml");
        assert_eq!(
            "kitti".parse::<Layout>(),
            Err("unknown dataset layout 'kitti': expected replica, tum, ros2 or euroc".into())
        );
    }
}
