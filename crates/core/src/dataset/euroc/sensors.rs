//! What the sensor.yaml files of a EuRoC dataset describe: each camera and the IMU, with their
//! placement on the body (the IMU's frame, docs/src/formats.md, "EuRoC (ASL) layout").

use crate::imu::ImuNoise;
use crate::{Intrinsics, Pose};

/// Radial-tangential (plumb bob) distortion, EuRoC's `distortion_coefficients: [k1, k2, p1, p2]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RadialTangential {
    pub k1: f64,
    pub k2: f64,
    pub p1: f64,
    pub p2: f64,
}

impl RadialTangential {
    /// No distortion (a rendered camera).
    pub const NONE: RadialTangential = RadialTangential {
        k1: 0.0,
        k2: 0.0,
        p1: 0.0,
        p2: 0.0,
    };

    pub fn to_array(self) -> [f64; 4] {
        [self.k1, self.k2, self.p1, self.p2]
    }

    pub fn from_array([k1, k2, p1, p2]: [f64; 4]) -> Self {
        Self { k1, k2, p1, p2 }
    }
}

/// How a camera's frames are stored: 8-bit grey PNG (EuRoC's own cameras), 8-bit RGB PNG, or
/// 16-bit grey PNG (TUM-VI's cameras; read and copied, never encoded: the GPU frames are 8-bit).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CameraColour {
    #[default]
    Grey,
    Rgb,
    Grey16,
}

/// One camera stream (`mav0/cam0`, `mav0/cam1`, …) as its sensor.yaml describes it.
#[derive(Clone, Debug, PartialEq)]
pub struct EurocCamera {
    /// Folder name under `mav0/`: `cam0`, `cam1`, …
    pub name: String,
    /// `comment:` of sensor.yaml (free text, one line).
    pub comment: String,
    /// `T_BS`: the camera's pose in the body (IMU) frame, camera-to-body.
    pub body_from_camera: Pose,
    pub rate_hz: f64,
    /// `resolution: [w, h]` and `intrinsics: [fu, fv, cu, cv]`.
    pub intrinsics: Intrinsics,
    /// TUM-VI's cameras are equidistant (Kannala-Brandt): their lens stays in `dso/camchain.yaml`,
    /// which is rewritten line by line, and this is [`RadialTangential::NONE`].
    pub distortion: RadialTangential,
    /// Not a sensor.yaml key: the writer picks the PNG colour type by it, the reader tells it
    /// from the first frame's PNG header (grey when the camera has no frame).
    pub colour: CameraColour,
}

/// The IMU (`mav0/imu0`) as its sensor.yaml describes it: Kalibr's noise model, continuous-time
/// densities.
#[derive(Clone, Debug, PartialEq)]
pub struct EurocImu {
    /// `comment:` of sensor.yaml (free text, one line).
    pub comment: String,
    /// `T_BS`: the identity when the body frame is the IMU's (docs/src/formats.md, "EuRoC (ASL) layout").
    pub body_from_imu: Pose,
    pub rate_hz: f64,
    /// rad / s / √Hz
    pub gyroscope_noise_density: f64,
    /// rad / s² / √Hz
    pub gyroscope_random_walk: f64,
    /// m / s² / √Hz
    pub accelerometer_noise_density: f64,
    /// m / s³ / √Hz
    pub accelerometer_random_walk: f64,
}

impl EurocImu {
    /// EuRoC's own ADIS16448 at 200 Hz (imu0/sensor.yaml of the published dataset; docs/src/formats.md, "EuRoC (ASL) layout").
    pub fn adis16448() -> Self {
        Self {
            comment: "VI-Sensor IMU (ADIS16448)".into(),
            body_from_imu: Pose::IDENTITY,
            rate_hz: 200.0,
            gyroscope_noise_density: 1.6968e-4,
            gyroscope_random_walk: 1.9393e-5,
            accelerometer_noise_density: 2.0e-3,
            accelerometer_random_walk: 3.0e-3,
        }
    }

    /// The four noise parameters, as the IMU model takes them.
    pub fn noise(&self) -> ImuNoise {
        ImuNoise {
            gyroscope_noise_density: self.gyroscope_noise_density,
            gyroscope_random_walk: self.gyroscope_random_walk,
            accelerometer_noise_density: self.accelerometer_noise_density,
            accelerometer_random_walk: self.accelerometer_random_walk,
        }
    }
}
