//! Continuous-time IMU noise parameters, named and dimensioned as Kalibr's `imu.yaml` names them
//! (Kalibr wiki, "IMU Noise Model").

use crate::CoreError;

/// White-noise densities and bias random walks of a gyroscope and an accelerometer, the same on
/// each axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImuNoise {
    /// σ_g, rad/s/√Hz.
    pub gyroscope_noise_density: f64,
    /// σ_bg, rad/s²/√Hz.
    pub gyroscope_random_walk: f64,
    /// σ_a, m/s²/√Hz.
    pub accelerometer_noise_density: f64,
    /// σ_ba, m/s³/√Hz.
    pub accelerometer_random_walk: f64,
}

impl ImuNoise {
    /// The ADIS16448 of the EuRoC MAV datasets, as each sequence's `mav0/imu0/sensor.yaml`
    /// publishes it (Burri et al., IJRR 2016).
    pub const ADIS16448_EUROC: ImuNoise = ImuNoise {
        gyroscope_noise_density: 1.6968e-04,
        gyroscope_random_walk: 1.9393e-05,
        accelerometer_noise_density: 2.0000e-3,
        accelerometer_random_walk: 3.0000e-3,
    };

    /// A perfect IMU: readings equal the truth and the biases stay where they start.
    pub const ZERO: ImuNoise = ImuNoise {
        gyroscope_noise_density: 0.0,
        gyroscope_random_walk: 0.0,
        accelerometer_noise_density: 0.0,
        accelerometer_random_walk: 0.0,
    };

    /// An error naming the first parameter that is negative or not finite.
    pub fn validate(&self) -> Result<(), CoreError> {
        for (name, value) in [
            ("gyroscope_noise_density", self.gyroscope_noise_density),
            ("gyroscope_random_walk", self.gyroscope_random_walk),
            (
                "accelerometer_noise_density",
                self.accelerometer_noise_density,
            ),
            ("accelerometer_random_walk", self.accelerometer_random_walk),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(CoreError::BadImuNoise { name, value });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_valid_and_bad_values_are_named() {
        assert!(ImuNoise::ADIS16448_EUROC.validate().is_ok());
        assert!(ImuNoise::ZERO.validate().is_ok());
        let bad = ImuNoise {
            accelerometer_random_walk: -1.0,
            ..ImuNoise::ZERO
        };
        let error = bad.validate().unwrap_err().to_string();
        assert!(error.contains("accelerometer_random_walk = -1"), "{error}");
        let nan = ImuNoise {
            gyroscope_noise_density: f64::NAN,
            ..ImuNoise::ZERO
        };
        assert!(nan.validate().is_err());
    }
}
