//! IMU perturbations (`imu_noise`, `imu_bias_step`, `imu_saturation`, `imu_drop`, `imu_jitter`)
//! and the camera–IMU time offset (`cam_imu_offset`), on the CPU: IMU samples are rows, not
//! frames.
//!
//! [`ImuSpec`] holds the items of a spec ([`items`]); [`ImuSpec::apply`] runs them on an IMU
//! stream and its ground truth ([`apply`]), one file per operation. Each draw is keyed by
//! (seed, item name, sample index, purpose) through [`crate::rng`], like every other draw.

mod added_noise;
mod apply;
mod bias_step;
pub mod items;
mod jitter;
mod sample_drop;
mod saturation;

pub use added_noise::AddedNoise;
pub use apply::{shift_stamp, ImuOrigin, ImuReport, ImuStream, PerturbedImu};
pub use bias_step::BiasStep;
pub use items::{is_imu_item, ImuSpec, PerSensor, SampleDrop, IMU_ITEMS};
pub use jitter::Jittered;
pub use sample_drop::Dropped;
pub use saturation::Saturated;
