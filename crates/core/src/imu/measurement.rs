//! The discrete-time IMU error model Kalibr and OpenVINS use: per sample, white noise of standard
//! deviation σ/√Δt on top of a bias that walks by σ_b·√Δt·N(0, 1) between samples (Kalibr wiki,
//! "IMU Noise Model", discrete-time equations; OpenVINS `Simulator::get_next_imu`).

use glam::DVec3;

use super::gaussian::{standard_normal, NoisePurpose};
use super::{ImuNoise, ImuReading};
use crate::CoreError;

/// Gyroscope and accelerometer biases, rad/s and m/s².
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ImuBias {
    pub gyroscope: DVec3,
    pub accelerometer: DVec3,
}

/// One IMU sample: the reading as measured, the noise-free truth and the biases in it (EuRoC's
/// ground truth lists them beside the state).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImuSample {
    /// Seconds.
    pub timestamp: f64,
    /// `truth + bias + white noise`.
    pub measured: ImuReading,
    pub truth: ImuReading,
    pub bias: ImuBias,
}

/// The noise of a sequence of samples at a fixed rate: sample `k` gets white noise drawn from
/// (seed, k, axis) and the bias reached after `k` steps of the walk from `initial_bias`.
#[derive(Clone, Debug)]
pub struct NoisyImu {
    noise: ImuNoise,
    seed: u64,
    /// Seconds between samples.
    dt: f64,
    index: u64,
    bias: ImuBias,
}

impl NoisyImu {
    pub fn new(
        noise: ImuNoise,
        rate_hz: f64,
        seed: u64,
        initial_bias: ImuBias,
    ) -> Result<Self, CoreError> {
        noise.validate()?;
        if !(rate_hz.is_finite() && rate_hz > 0.0) {
            return Err(CoreError::BadRate { hz: rate_hz });
        }
        Ok(Self {
            noise,
            seed,
            dt: 1.0 / rate_hz,
            index: 0,
            bias: initial_bias,
        })
    }

    fn normals(&self, purpose: NoisePurpose) -> DVec3 {
        DVec3::from_array(std::array::from_fn(|axis| {
            standard_normal(self.seed, self.index, axis, purpose)
        }))
    }

    /// The next sample, measuring `truth` at `timestamp`; then the biases take one step.
    pub fn measure(&mut self, timestamp: f64, truth: ImuReading) -> ImuSample {
        let n = &self.noise;
        // σ_d = σ / √Δt (white), σ_bd = σ_b · √Δt (random walk).
        let (white, walk) = (1.0 / self.dt.sqrt(), self.dt.sqrt());
        let sample = ImuSample {
            timestamp,
            measured: ImuReading {
                gyroscope: truth.gyroscope
                    + self.bias.gyroscope
                    + self.normals(NoisePurpose::GyroscopeWhite)
                        * (n.gyroscope_noise_density * white),
                accelerometer: truth.accelerometer
                    + self.bias.accelerometer
                    + self.normals(NoisePurpose::AccelerometerWhite)
                        * (n.accelerometer_noise_density * white),
            },
            truth,
            bias: self.bias,
        };
        self.bias.gyroscope +=
            self.normals(NoisePurpose::GyroscopeBiasWalk) * (n.gyroscope_random_walk * walk);
        self.bias.accelerometer += self.normals(NoisePurpose::AccelerometerBiasWalk)
            * (n.accelerometer_random_walk * walk);
        self.index += 1;
        sample
    }
}
