//! Depth corruptions: one file per corruption (parameters, GPU passes, CPU twin, tests), plus
//! the shared in-place depth pass.

pub mod depth_edge_erosion;
pub mod depth_missing;
pub mod depth_noise;
pub mod depth_noise_kinect;
pub mod depth_pass;
pub mod depth_range;
pub mod depth_sensor;
