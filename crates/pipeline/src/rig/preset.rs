//! Rig presets: the cameras and IMU a rig name stands for, placed on the body as EuRoC
//! places them (the body frame is the IMU's; docs/src/formats.md, "EuRoC (ASL) layout"). `rgbd` is the
//! one RGB-D camera of a render without a rig; `rgbd-imu` that camera on a RealSense
//! D435i-like body with its IMU, written in the TUM layout with the IMU beside it.

use std::path::Path;

use glam::{DQuat, DVec3};
use rslam_core::dataset::euroc::{CameraColour, EurocCamera, EurocImu, RadialTangential};
use rslam_core::dataset::ros2::BagNames;
use rslam_core::{Intrinsics, Pose};

use super::rig_file::read_rig_file;
use crate::{JobPart, PipelineError};

/// The names of the rigs written in the EuRoC layout ([`Rig::preset`]).
pub const RIG_NAMES: [&str; 2] = ["stereo", "stereo-imu"];

/// Every rig name, in the order the help and the errors list them.
pub const PRESET_NAMES: [&str; 4] = ["rgbd", "rgbd-imu", "stereo", "stereo-imu"];

/// Distance between the two cameras' centres, along cam0's x axis (right), metres. About the
/// EuRoC MAV's VI-Sensor baseline (docs/src/formats.md, "EuRoC (ASL) layout").
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
/// camera axes are OpenCV's (x right, y down, z forward), rslam's own (docs/src/formats.md, "Camera conventions"), so the
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

/// The RGB-D camera's pose in the IMU frame of a RealSense D435i (`T_BS`, camera-to-body, body
/// = IMU), row-major: `IMU.T_b_c1` of ORB-SLAM3 v1.0's
/// `Examples/RGB-D-Inertial/RealSense_D435i.yaml` (UZ-SLAMLab/ORB_SLAM3 at 0df83dd), the colour
/// camera 2.0 cm to the IMU's −x, 0.5 cm +y, 1.1 cm +z, axes within 0.8° of the IMU's. Its 6
/// digits are not quite a rotation: [`Pose::from_row_major`] takes the nearest one.
const D435I_T_B_C1: [f64; 16] = [
    0.999903,
    -0.0138036,
    -0.00208099,
    -0.0202141,
    0.0137985,
    0.999902,
    -0.00243498,
    0.00505961,
    0.0021144,
    0.00240603,
    0.999995,
    0.0114047,
    0.0,
    0.0,
    0.0,
    1.0,
];

/// The D435i's IMU (Bosch BMI055) at 200 Hz, at the body's origin. Noise densities: the
/// BMI055 datasheet's 0.014 °/s/√Hz (gyroscope) and 150 µg/√Hz (accelerometer), as ORB-SLAM3's
/// RealSense_D435i.yaml notes them beside its keys (2.44e-4 rad/s/√Hz, 1.47e-3 m/s²/√Hz); the
/// datasheet gives no random walks, so those are that file's `IMU.GyroWalk` 1e-6 rad/s²/√Hz and
/// `IMU.AccWalk` 1e-4 m/s³/√Hz. (The file's own `NoiseGyro` 1e-2 and `NoiseAcc` 1e-1 are
/// inflated some 40× and 70× over the datasheet, for a real device's unmodelled errors; rslam's
/// readings have none, so it writes what it synthesises.)
pub fn d435i_imu() -> EurocImu {
    EurocImu {
        comment: "RealSense D435i IMU (Bosch BMI055)".into(),
        body_from_imu: Pose::IDENTITY,
        rate_hz: 200.0,
        gyroscope_noise_density: 2.44e-4,
        gyroscope_random_walk: 1.0e-6,
        accelerometer_noise_density: 1.47e-3,
        accelerometer_random_walk: 1.0e-4,
    }
}

/// What a rig name asks a render for.
// One per job: the size of the rig variant does not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub enum RigPreset {
    /// `rgbd`: one RGB-D camera, the render without a rig (any core layout).
    Rgbd,
    /// `rgbd-imu`: [`Rig::rgbd_imu`] of the render's camera and rate, in the TUM layout.
    RgbdImu,
    /// `stereo`, `stereo-imu`: a rig in the EuRoC layout.
    Euroc(Rig),
}

impl RigPreset {
    /// The preset `name` stands for, or the rig of a `.toml` file ([`read_rig_file`]); the
    /// error lists the valid names.
    pub fn by_name(name: &str) -> Result<Self, PipelineError> {
        match name {
            "rgbd" => Ok(Self::Rgbd),
            "rgbd-imu" => Ok(Self::RgbdImu),
            _ if RIG_NAMES.contains(&name) => Rig::preset(name).map(Self::Euroc),
            _ if name.ends_with(".toml") => read_rig_file(Path::new(name)).map(Self::Euroc),
            other => Err(unknown_rig(
                other,
                &[&PRESET_NAMES[..], &["a rig file (FILE.toml)"]].concat(),
            )),
        }
    }
}

fn unknown_rig(name: &str, valid: &[&str]) -> PipelineError {
    PipelineError::option(
        JobPart::Rig,
        format!(
            "'{}': expected one of {}",
            rslam_core::printable(name),
            valid.join(", ")
        ),
    )
}

/// The sensors of a rig: cameras (`cam0`, `cam1`, …, each with its pose on the body) and an
/// optional IMU.
#[derive(Clone, Debug, PartialEq)]
pub struct Rig {
    /// The rig name, for the manifest.
    pub name: String,
    pub cameras: Vec<EurocCamera>,
    /// Per camera: its stamps are its capture times plus this (its clock runs ahead by it), ns.
    pub time_offsets_ns: Vec<i64>,
    pub imu: Option<EurocImu>,
    /// Its topics and frames in a ROS 2 bag where not EuRoC's (a rig file's `[ros2]` table).
    pub bag_names: BagNames,
}

impl Rig {
    /// A rig written in the EuRoC layout by its name; the error lists those names.
    pub fn preset(name: &str) -> Result<Self, PipelineError> {
        match name {
            "stereo" => Ok(Self::stereo()),
            "stereo-imu" => Ok(Self::stereo_imu()),
            other => Err(unknown_rig(other, &RIG_NAMES)),
        }
    }

    /// `rgbd-imu`: one RGB-D camera `camera` at `rate_hz` (a render's camera and rate)
    /// where a RealSense D435i has its colour camera, [`D435I_T_B_C1`], and the D435i's IMU
    /// ([`d435i_imu`]) at the body's origin.
    pub fn rgbd_imu(camera: Intrinsics, rate_hz: f64) -> Self {
        Self {
            name: "rgbd-imu".into(),
            cameras: vec![EurocCamera {
                name: "cam0".into(),
                comment: "rslam RGB-D camera (RealSense D435i colour-camera pose)".into(),
                body_from_camera: Pose::from_row_major(&D435I_T_B_C1),
                rate_hz,
                intrinsics: camera,
                distortion: RadialTangential::NONE,
                colour: CameraColour::Rgb,
            }],
            time_offsets_ns: vec![0],
            imu: Some(d435i_imu()),
            bag_names: BagNames::default(),
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
            time_offsets_ns: vec![0, 0],
            imu: None,
            bag_names: BagNames::default(),
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
        assert_eq!(err, "rig: 'rgbd': expected one of stereo, stereo-imu");
        assert_eq!(RigPreset::by_name("rgbd").unwrap(), RigPreset::Rgbd);
        assert_eq!(RigPreset::by_name("rgbd-imu").unwrap(), RigPreset::RgbdImu);
        assert_eq!(
            RigPreset::by_name("stereo").unwrap(),
            RigPreset::Euroc(stereo)
        );
        let err = RigPreset::by_name("mono").unwrap_err().to_string();
        assert_eq!(
            err,
            "rig: 'mono': expected one of rgbd, rgbd-imu, stereo, stereo-imu, a rig file (FILE.toml)"
        );
    }

    /// The camera is the one given, at ORB-SLAM3's D435i `IMU.T_b_c1` (to the yaml's 6 digits:
    /// the nearest rotation moves no entry by more than 1e-5), the IMU the BMI055's at 200 Hz.
    #[test]
    fn rgbd_imu_is_the_given_camera_at_the_d435i_pose_with_its_imu() {
        let rig = Rig::rgbd_imu(Intrinsics::TUM, 30.0);
        assert_eq!(rig.name, "rgbd-imu");
        let [camera] = rig.cameras.as_slice() else {
            panic!("one camera: {:?}", rig.cameras)
        };
        assert_eq!(camera.intrinsics, Intrinsics::TUM);
        assert_eq!(camera.rate_hz, 30.0);
        assert_eq!(camera.colour, CameraColour::Rgb);
        assert_eq!(camera.distortion, RadialTangential::NONE);
        let written = camera.body_from_camera.to_row_major();
        for (got, want) in written.iter().zip(D435I_T_B_C1) {
            assert!((got - want).abs() < 1e-5, "{written:?}");
        }
        // the colour camera sits about 2 cm from the IMU, mostly along its -x
        let t = camera.body_from_camera.translation;
        assert!((t.length() - 0.0238).abs() < 1e-3 && t.x < -0.02, "{t}");
        let imu = rig.imu.as_ref().unwrap();
        assert_eq!(imu.rate_hz, 200.0);
        assert_eq!(imu.body_from_imu, Pose::IDENTITY);
        // BMI055 datasheet densities in SI units
        assert!((imu.gyroscope_noise_density - 0.014_f64.to_radians()).abs() < 1e-6);
        assert!((imu.accelerometer_noise_density - 150e-6 * 9.80665).abs() < 1e-5);
        assert_eq!(imu.gyroscope_random_walk, 1e-6);
        assert_eq!(imu.accelerometer_random_walk, 1e-4);
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
