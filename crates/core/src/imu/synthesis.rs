//! IMU sequences from a spline: ideal readings at a fixed rate over the spline's valid range,
//! through the noise model.

use glam::DVec3;

use super::reading::{ideal_reading, GRAVITY_WORLD};
use super::{ImuBias, ImuNoise, ImuSample, NoisyImu};
use crate::limits::MAX_IMU_SAMPLES;
use crate::{CoreError, Pose, SplineSe3};

/// How to synthesise an IMU: its rate, where it sits on the body, its noise and the seed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImuSynthesis {
    pub rate_hz: f64,
    /// The IMU's pose in the body (camera) frame, `T_body_imu`.
    pub body_from_imu: Pose,
    pub gravity_world: DVec3,
    pub noise: ImuNoise,
    /// Biases of the first sample.
    pub initial_bias: ImuBias,
    pub seed: u64,
}

impl Default for ImuSynthesis {
    /// EuRoC's IMU: an ADIS16448 at 200 Hz, here at the body's origin, unbiased at the start.
    fn default() -> Self {
        Self {
            rate_hz: 200.0,
            body_from_imu: Pose::IDENTITY,
            gravity_world: GRAVITY_WORLD,
            noise: ImuNoise::ADIS16448_EUROC,
            initial_bias: ImuBias::default(),
            seed: 0,
        }
    }
}

/// Samples at `start + k / rate_hz` for every such time in the spline's valid range.
pub fn synthesize_imu(
    spline: &SplineSe3,
    options: &ImuSynthesis,
) -> Result<Vec<ImuSample>, CoreError> {
    let mut imu = NoisyImu::new(
        options.noise,
        options.rate_hz,
        options.seed,
        options.initial_bias,
    )?;
    let range = spline.valid_range();
    // The small allowance keeps the last sample when the range is a whole number of periods.
    // Finite (or +∞ for an absurd rate): the range and the rate were checked.
    let steps = ((range.end - range.start) * options.rate_hz + 1e-6).floor();
    if steps >= MAX_IMU_SAMPLES as f64 {
        return Err(CoreError::TooManyImuSamples {
            samples: steps + 1.0,
            max: MAX_IMU_SAMPLES,
        });
    }
    (0..=steps as u64)
        .map(|k| {
            let t = (range.start + k as f64 / options.rate_hz).min(range.end);
            let truth = ideal_reading(spline, t, &options.body_from_imu, options.gravity_world)?;
            Ok(imu.measure(t, truth))
        })
        .collect()
}
