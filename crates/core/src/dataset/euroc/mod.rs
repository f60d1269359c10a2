//! The EuRoC MAV (ASL) dataset layout (docs/src/formats.md, "EuRoC (ASL) layout"), for rigs with cameras
//! and an IMU; ORB-SLAM3's stereo(-inertial) examples, OpenVINS, VINS-Fusion, Kalibr and evo
//! read it.
//!
//! ```text
//! <root>/mav0/cam0/data/<t_ns>.png, cam0/data.csv, cam0/sensor.yaml   (cam1, … the same)
//!             imu0/data.csv, imu0/sensor.yaml
//!             state_groundtruth_estimate0/data.csv
//! <root>/orbslam3_stereo.yaml            (two cameras or more)
//!        orbslam3_stereo_inertial.yaml   (two cameras or more and an IMU)
//! ```
//!
//! [`EurocWriter`] writes it (frames as they arrive, the CSV and YAML files and the manifest at
//! the end). The two `orbslam3_*.yaml` files are ORB-SLAM3 v1.0 settings for cam0 (left,
//! `Camera1`) and cam1 (right, `Camera2`) with their distortion, `Stereo.T_c1_c2` (cam1's pose
//! in cam0's frame, from the two `T_BS`) and, for the inertial one, `IMU.T_b_c1` (cam0's `T_BS`)
//! and imu0's noise densities, laid out as ORB-SLAM3's `Examples/Stereo(-Inertial)/EuRoC.yaml`.
//! [`read_euroc`] reads the layout back, rslam's or a published sequence (it does not need the
//! settings files), or TUM-VI's EuRoC-style export (`dso/camchain.yaml` and `imu_config.yaml`
//! in place of the sensor.yaml files, `mocap0/` for the ground truth; [`TumViCalibration`]). Timestamps are integer nanoseconds; quaternions in the ground truth are written **w** first. Plain data:
//! [`EurocCamera`], [`EurocImu`] (sensor.yaml), [`EurocFrame`], [`ImuSample`],
//! [`GroundTruthState`] (data.csv rows).

mod camchain;
mod csv;
mod reader;
mod samples;
mod sensor_yaml;
mod sensors;
mod tum_vi;
mod writer;

#[cfg(test)]
mod tests;

pub use camchain::{read_camchain, Camchain, CamchainCamera};
pub use csv::{ground_truth_csv, imu_csv, CAMERA_HEADER, GROUND_TRUTH_HEADER, IMU_HEADER};
pub use reader::{
    read_euroc, read_euroc_without_frames, read_inertial, EurocCameraFrames, EurocDataset,
    EurocImuSamples,
};
pub use samples::{nanoseconds_from_seconds, EurocFrame, GroundTruthState, ImuSample};
pub use sensor_yaml::{CAMERA_YAML_FIRST_LINE, IMU_YAML_FIRST_LINE};
pub use sensors::{CameraColour, EurocCamera, EurocImu, RadialTangential};
pub use tum_vi::{TumViCalibration, CAMCHAIN_FILE, IMU_CONFIG_FILE, TUM_VI_CALIBRATION_DIR};
pub use writer::{
    inertial_files, EurocWriter, GROUND_TRUTH_DIR, IMU_DIR, MAV_DIR, MOCAP_DIR,
    ORBSLAM3_STEREO_FILE, ORBSLAM3_STEREO_INERTIAL_FILE,
};
