//! The layouts a suite's sequences are written in and a method reads (`reads = "euroc"`): the
//! two of one RGB-D camera, and EuRoC's for a rig.

use std::fmt;
use std::str::FromStr;

use rslam_core::dataset::euroc::ORBSLAM3_STEREO_FILE;
use rslam_core::dataset::DatasetFormat;
use rslam_pipeline::rig::RIG_NAMES;

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

    /// The file `{camera}` stands for, in the dataset folder: the camera's parameters, or for a
    /// rig ORB-SLAM3's stereo settings (`orbslam3_stereo_inertial.yaml` lies beside it when the
    /// rig has an IMU).
    pub fn camera_file(self) -> &'static str {
        match self {
            Self::Camera(DatasetFormat::Replica) => "cam_params.json",
            Self::Camera(DatasetFormat::Tum) => "orbslam3.yaml",
            Self::Euroc => ORBSLAM3_STEREO_FILE,
        }
    }

    /// How to make a suite of this layout, for an error.
    pub fn how_to_make(self) -> String {
        match self {
            Self::Camera(format) => format!("`rslam suite init --format {format}`"),
            Self::Euroc => format!(
                "rows that say format = \"euroc\" and rig = one of {}",
                RIG_NAMES.join(", ")
            ),
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
                format!("unknown dataset layout '{s}': expected replica, tum or euroc")
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
            Layout::Euroc,
        ] {
            assert_eq!(layout.name().parse::<Layout>(), Ok(layout));
        }
        assert_eq!(Layout::Euroc.camera_file(), "orbslam3_stereo.yaml");
        assert_eq!(
            "kitti".parse::<Layout>(),
            Err("unknown dataset layout 'kitti': expected replica, tum or euroc".into())
        );
    }
}
