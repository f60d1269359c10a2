//! Multi-sensor rigs: several cameras and an IMU on one moving body, rendered into the EuRoC
//! layout (docs/src/formats.md, "EuRoC (ASL) layout").
//!
//! Conventions: the body frame is the IMU's (EuRoC's); each camera's `body_from_camera` is its
//! sensor.yaml `T_BS`, camera axes OpenCV's (x right, y down, z forward). The scene's path is
//! cam0's path; the body follows it at `body_from_cam0⁻¹` along a cubic B-spline on SE(3), which
//! every sensor samples at its own rate over the spline's valid range. Camera `i` corrupts its
//! frames with seed [`camera_seed`]`(seed, i)` (cam0: the job's seed), the IMU draws its noise
//! with [`imu_seed`]`(seed)`.
//!
//! - [`rig_file`]: a rig file (`FILE.toml`), a rig of the user's own in the EuRoC layout.
//! - [`preset`]: the rig presets ([`RigPreset`]): `rgbd` (the one RGB-D camera of a render
//!   without a rig), `rgbd-imu` ([`Rig::rgbd_imu`]), `stereo` and `stereo-imu` ([`Rig::stereo`],
//!   [`Rig::stereo_imu`]).
//! - [`euroc_render`]: a rig in the EuRoC layout, planned for a [`crate::Job`].
//! - [`rgbd_imu_render`]: the `rgbd-imu` rig, planned: the TUM layout plus the IMU's files as
//!   EuRoC has them and ORB-SLAM3's RGB-D-inertial settings.
//! - [`rgbd_imu_perturb`]: the inertial files an `rgbd-imu` output's perturbed copy keeps.
//! - [`euroc_perturb`]: a recorded EuRoC dataset (MH_01_easy, …) copied with
//!   every camera's frames corrupted (image corruptions) and its IMU perturbed (IMU items); also
//!   TUM-VI's EuRoC-style export, whose own files (`dso/`, `mocap0/`) [`tum_vi_files`] keeps.
//!
//! - [`imu_items`]: the spec's IMU items (`imu_noise`, `imu_bias_step`, …) on the rig's IMU
//!   stream and ground truth, `cam_imu_offset` on the camera stamps; refused without an IMU.
//!
//! - [`calibration`]: [`PerturbedRig`], the rig as mounted and as calibrated under the spec's
//!   `baseline` and `extrinsic_*` items.
//!
//! Image and depth items reach every camera, or only the one they name (`cam1:fog:3`,
//! [`rslam_perturb::PerturbSpec::for_camera`]).
//!
//! An unfinished rig render resumes frame by frame (each camera from its first missing frame),
//! as a one-camera render does, and so does an unfinished EuRoC perturb.

mod bag_imu;
pub mod calibration;
pub mod euroc_perturb;
pub mod euroc_render;
mod imu_items;
mod imu_stream;
mod motion;
pub mod preset;
pub mod rgbd_imu_perturb;
pub mod rgbd_imu_render;
mod rig_bag_names;
pub mod rig_file;
mod seeds;
mod tum_vi_files;

pub(crate) use bag_imu::perturb_bag_imus;
pub use calibration::{PerturbedRig, PER_FRAME_FILE};
pub use euroc_perturb::is_euroc_input;
pub use euroc_render::{rig_camera_frames, CameraFrames};
pub use imu_items::with_imu_report;
pub use preset::{
    d435i_imu, Rig, RigPreset, EUROC_CAM0_INTRINSICS, PRESET_NAMES, RIG_NAMES, STEREO_BASELINE_M,
};
pub use rgbd_imu_render::{rgbd_imu_frame_count, ORBSLAM3_RGBD_INERTIAL_FILE};
pub use seeds::{camera_seed, imu_seed};
