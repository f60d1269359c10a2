//! Synthetic IMU readings for multi-sensor rigs.
//!
//! A [`SplineSe3`](crate::SplineSe3) through the camera trajectory gives the body's motion at any
//! instant; [`ideal_reading`] turns it into what a perfect IMU at the extrinsic `T_body_imu`
//! measures (angular velocity and specific force in the IMU's axes, gravity [`GRAVITY_WORLD`]);
//! [`NoisyImu`] adds Kalibr's discrete noise model ([`ImuNoise`]: white noise and bias random
//! walk), drawn from the counter-based hash so that a seed fixes the sequence; [`synthesize_imu`]
//! does both at a fixed rate over the spline's valid range, and [`dead_reckon`] integrates readings
//! back into a pose (the consistency check).

pub mod allan;
mod gaussian;
mod measurement;
mod noise;
mod reading;
mod strapdown;
mod synthesis;

#[cfg(test)]
mod allan_tests;
#[cfg(test)]
mod consistency_tests;

pub use gaussian::{standard_normal, NoisePurpose};
pub use measurement::{ImuBias, ImuSample, NoisyImu};
pub use noise::ImuNoise;
pub use reading::{ideal_reading, ImuReading, GRAVITY_WORLD};
pub use strapdown::{dead_reckon, InertialState};
pub use synthesis::{synthesize_imu, ImuSynthesis};
