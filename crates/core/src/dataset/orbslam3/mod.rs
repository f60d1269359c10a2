//! ORB-SLAM3 v1.0 settings files (`File.version: "1.0"`, read by its `Settings` class) for the
//! datasets rslam writes: RGB-D for the TUM layout ([`settings`], `orbslam3.yaml`), stereo and
//! stereo-inertial for the EuRoC layout ([`stereo_settings`], [`stereo_inertial_settings`],
//! `orbslam3_stereo.yaml` and `orbslam3_stereo_inertial.yaml`), RGB-D-inertial for the `rgbd-imu`
//! rig ([`rgbd_inertial_settings`], `orbslam3_rgbd_inertial.yaml`), each with every key its loader
//! and viewer read.

mod imu;
mod rgbd;
mod stereo;

#[cfg(test)]
mod stereo_tests;

pub use rgbd::{rgbd_inertial_settings, settings};
pub use stereo::{stereo_inertial_settings, stereo_pair_problem, stereo_settings};
