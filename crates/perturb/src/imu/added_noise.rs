//! `imu_noise:K` on recorded readings: they hold their sensor's noise already, so independent
//! noise of (K² − 1)× its variances is added (variances of independent noises add), white noise
//! and bias walk alike, through core's discrete model ([`NoisyImu`]). The added walk is part of
//! the true bias from then on.

use rslam_core::dataset::euroc::ImuSample;
use rslam_core::imu::{ImuBias, ImuNoise, ImuReading, NoisyImu};
use serde::Serialize;

use super::items::NOISE;
use crate::rng::RngKey;

/// The noise added, Kalibr's parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct AddedNoise {
    pub gyroscope_noise_density: f64,
    pub gyroscope_random_walk: f64,
    pub accelerometer_noise_density: f64,
    pub accelerometer_random_walk: f64,
}

/// The noise that makes `nominal` `scale` times larger, or `None` for a scale below 1 (noise
/// cannot be taken out of a reading).
pub fn added_noise(nominal: ImuNoise, scale: f64) -> Option<ImuNoise> {
    let factor = (scale * scale - 1.0).sqrt();
    (scale >= 1.0).then_some(ImuNoise {
        gyroscope_noise_density: nominal.gyroscope_noise_density * factor,
        gyroscope_random_walk: nominal.gyroscope_random_walk * factor,
        accelerometer_noise_density: nominal.accelerometer_noise_density * factor,
        accelerometer_random_walk: nominal.accelerometer_random_walk * factor,
    })
}

/// Adds `noise` at `rate_hz` to the readings; returns the walk added to each sample's biases.
/// The noise's seed is keyed by (seed, `imu_noise`) like every other draw.
pub fn add_noise(
    samples: &mut [ImuSample],
    noise: ImuNoise,
    rate_hz: f64,
    seed: u64,
) -> Result<Vec<ImuBias>, rslam_core::CoreError> {
    let key = RngKey::new(seed, NOISE, 0, 0).0;
    let noise_seed = ((key[0] as u64) << 32) | key[1] as u64;
    let mut imu = NoisyImu::new(noise, rate_hz, noise_seed, ImuBias::default())?;
    Ok(samples
        .iter_mut()
        .map(|s| {
            let recorded = ImuReading {
                gyroscope: s.gyro,
                accelerometer: s.accel,
            };
            let noisy = imu.measure(s.t_ns as f64 * 1e-9, recorded);
            s.gyro = noisy.measured.gyroscope;
            s.accel = noisy.measured.accelerometer;
            noisy.bias
        })
        .collect())
}

impl From<ImuNoise> for AddedNoise {
    fn from(n: ImuNoise) -> Self {
        Self {
            gyroscope_noise_density: n.gyroscope_noise_density,
            gyroscope_random_walk: n.gyroscope_random_walk,
            accelerometer_noise_density: n.accelerometer_noise_density,
            accelerometer_random_walk: n.accelerometer_random_walk,
        }
    }
}
