//! Common types of rslam, free of any GPU code.
//!
//! Data flow: a [`Trajectory`] of camera-to-world [`Pose`]s and an [`Intrinsics`] go to the
//! renderer; it hands back [`RgbImage`] / [`DepthImage`] pairs, which the `dataset` writers encode
//! into the Replica or TUM layout, manifest last. `trajectory_io` reads and writes the trajectory
//! file formats that SLAM systems and `rslam eval` use; `mesh_io` reads meshes and point clouds,
//! and [`SurfaceBvh`] answers nearest-surface and first-hit queries on them (ray casting,
//! reconstruction metrics and their visibility culling).
//!
//! For inertial sensors, a [`SplineSe3`] (a C² cubic B-spline on SE(3) through a trajectory's
//! poses) gives the body's pose, velocity and acceleration at any instant, and [`imu`] turns it
//! into ideal and noisy IMU readings (Kalibr's noise model) at a rig's IMU extrinsic.

pub mod dataset;
mod distortion;
mod error;
pub mod hash;
mod image_buffer;
mod image_pool;
pub mod imu;
mod intrinsics;
mod limited_read;
pub mod limits;
mod mask_image;
pub mod mesh_io;
mod nearest_time;
mod pose;
mod remove_if_present;
pub mod se3;
pub mod splat_io;
mod spline_se3;
mod surface_bvh;
#[cfg(test)]
mod test_motion;
mod trajectory;
pub mod trajectory_io;

pub use distortion::{Distortion, UNDISTORT_TOLERANCE};
pub use error::{printable, CoreError};
pub use image_buffer::{DepthImage, RgbImage};
pub use image_pool::ImagePool;
pub use intrinsics::{Intrinsics, REPLICA_RATE_HZ, TUM_RATE_HZ};
pub use limited_read::{read_limited, read_text_file};
pub use mask_image::MaskImage;
pub use nearest_time::nearest_time;
pub use pose::Pose;
pub use remove_if_present::remove_if_present;
pub use spline_se3::{SplineSe3, SplineState, TimeRange};
pub use surface_bvh::{RaySurfaceHit, SurfaceBvh, SurfacePoint};
pub use trajectory::Trajectory;
