//! The EuRoC MAV (ASL) dataset layout (formats.md, "EuRoC (ASL) layout"), for rigs with cameras
//! and an IMU; ORB-SLAM3's stereo(-inertial) examples, OpenVINS, VINS-Fusion, Kalibr and evo
//! read it.
//!
//! ```text
//! <root>/mav0/cam0/data/<t_ns>.png, cam0/data.csv, cam0/sensor.yaml   (cam1, … the same)
//!             imu0/data.csv, imu0/sensor.yaml
//!             state_groundtruth_estimate0/data.csv
//! ```
//!
//! [`EurocWriter`] writes it (frames as they arrive, the CSV and YAML files and the manifest at
//! the end); [`read_euroc`] reads it back, rslam's or a published sequence. Timestamps are
//! integer nanoseconds; quaternions in the ground truth are written **w** first. Plain data:
//! [`EurocCamera`], [`EurocImu`] (sensor.yaml), [`EurocFrame`], [`ImuSample`],
//! [`GroundTruthState`] (data.csv rows).

mod csv;
mod reader;
mod samples;
mod sensor_yaml;
mod sensors;
mod writer;

#[cfg(test)]
mod tests;

pub use csv::{CAMERA_HEADER, GROUND_TRUTH_HEADER, IMU_HEADER};
pub use reader::{read_euroc, EurocCameraFrames, EurocDataset, EurocImuSamples};
pub use samples::{nanoseconds_from_seconds, EurocFrame, GroundTruthState, ImuSample};
pub use sensor_yaml::{CAMERA_YAML_FIRST_LINE, IMU_YAML_FIRST_LINE};
pub use sensors::{CameraColour, EurocCamera, EurocImu, RadialTangential};
pub use writer::{EurocWriter, GROUND_TRUTH_DIR, IMU_DIR, MAV_DIR};
