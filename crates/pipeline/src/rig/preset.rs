//! Rig presets: the cameras and IMU a `--rig` name stands for, placed on the body as EuRoC
//! places them (the body frame is the IMU's; formats.md, "EuRoC (ASL) layout").

use glam::{DQuat, DVec3};
use rslam_core::dataset::euroc::{CameraColour, EurocCamera, EurocImu, RadialTangential};
use rslam_core::{Intrinsics, Pose};

use crate::PipelineError;

/// The `--rig` names, in the order `rslam render --help` and the errors list them.
pub const RIG_NAMES: [&str; 2] = ["stereo", "stereo-imu"];

/// Distance between the two cameras' centres, along cam0's x axis (right), metres. About the
/// EuRoC MAV's VI-Sensor baseline (formats.md).
pub const STEREO_BASELINE_M: f64 = 0.11;

/// EuRoC cam0's pinhole intrinsics (MH_01_easy `cam0/sensor.yaml`), 752×480. Rendered frames
/// have no distortion: the pair is a rectified one.
pub const EUROC_CAM0_INTRINSICS: Intrinsics = Intrinsics {
    width: 752,
    height: 480,
    fx: 458.654,
    fy: 457.296,
    cx: 367.215,
    cy: 248.375,
};

/// EuRoC's camera rate, Hz.
pub const EUROC_CAMERA_RATE_HZ: f64 = 20.0;

/// EuRoC MH_01_easy cam0's `T_BS` (camera-to-body, body = IMU), row-major, as published. EuRoC's
/// camera axes are OpenCV's (x right, y down, z forward), rslam's own (formats.md), so the
/// matrix is used as it is.
const EUROC_MH01_CAM0_T_BS: [f64; 16] = [
    0.0148655429818,
    -0.999880929698,
    0.00414029679422,
    -0.0216401454975,
    0.999557249008,
    0.0149672133247,
    0.025715529948,
    -0.064676986768,
    -0.0257744366974,
    0.00375618835797,
    0.999660727178,
    0.00981073058949,
    0.0,
    0.0,
    0.0,
    1.0,
];

/// The sensors of a rig: cameras (`cam0`, `cam1`, …, each with its pose on the body) and an
/// optional IMU.
#[derive(Clone, Debug, PartialEq)]
pub struct Rig {
    /// The `--rig` name, for the manifest.
    pub name: String,
    pub cameras: Vec<EurocCamera>,
    pub imu: Option<EurocImu>,
}

impl Rig {
    /// A preset by its `--rig` name; the error lists the valid names.
    pub fn preset(name: &str) -> Result<Self, PipelineError> {
        match name {
            "stereo" => Ok(Self::stereo()),
            "stereo-imu" => Ok(Self::stereo_imu()),
            other => Err(PipelineError::option(
                "--rig",
                format!(
                    "'{}': expected one of {}",
                    rslam_core::printable(other),
                    RIG_NAMES.join(", ")
                ),
            )),
        }
    }

    /// Two cameras like the EuRoC MAV's: 752×480 grey at 20 Hz with EuRoC cam0's intrinsics and
    /// no distortion; cam0 at EuRoC MH_01's cam0 `T_BS`, cam1 the same camera moved
    /// [`STEREO_BASELINE_M`] along cam0's x axis (to its right), optical axes parallel.
    pub fn stereo() -> Self {
        let body_from_cam0 = Pose::from_row_major(&EUROC_MH01_CAM0_T_BS);
        let cam0_from_cam1 = Pose::new(DQuat::IDENTITY, DVec3::X * STEREO_BASELINE_M);
        let camera = |name: &str, comment: &str, body_from_camera: Pose| EurocCamera {
            name: name.into(),
            comment: comment.into(),
            body_from_camera,
            rate_hz: EUROC_CAMERA_RATE_HZ,
            intrinsics: EUROC_CAM0_INTRINSICS,
            distortion: RadialTangential::NONE,
            colour: CameraColour::Grey,
        };
        Self {
            name: "stereo".into(),
            cameras: vec![
                camera(
                    "cam0",
                    "rslam stereo left (EuRoC cam0 pose)",
                    body_from_cam0,
                ),
                camera(
                    "cam1",
                    "rslam stereo right (cam0 moved 0.11 m along its x axis)",
                    body_from_cam0.compose(&cam0_from_cam1),
                ),
            ],
            imu: None,
        }
    }

    /// [`Rig::stereo`] and EuRoC's ADIS16448 at 200 Hz, at the body's origin (the body is the
    /// IMU).
    pub fn stereo_imu() -> Self {
        Self {
            name: "stereo-imu".into(),
            imu: Some(EurocImu::adis16448()),
            ..Self::stereo()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_by_name_and_an_unknown_name_lists_the_valid_ones() {
        let stereo = Rig::preset("stereo").unwrap();
        assert_eq!(stereo.cameras.len(), 2);
        assert!(stereo.imu.is_none());
        let stereo_imu = Rig::preset("stereo-imu").unwrap();
        assert_eq!(stereo_imu.cameras, stereo.cameras);
        assert_eq!(stereo_imu.imu.as_ref().unwrap().rate_hz, 200.0);
        let err = Rig::preset("rgbd").unwrap_err().to_string();
        assert_eq!(err, "--rig: 'rgbd': expected one of stereo, stereo-imu");
    }

    #[test]
    fn cam1_is_cam0_moved_along_its_own_x_axis() {
        let rig = Rig::stereo();
        let cam0_from_cam1 = rig.cameras[0]
            .body_from_camera
            .inverse()
            .compose(&rig.cameras[1].body_from_camera);
        assert!((cam0_from_cam1.translation - DVec3::X * STEREO_BASELINE_M).length() < 1e-12);
        assert!(cam0_from_cam1.rotation.angle_between(DQuat::IDENTITY) < 1e-12);
    }
}
