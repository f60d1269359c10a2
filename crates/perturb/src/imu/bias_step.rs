//! `imu_bias_step:GYRO/ACC`: both biases jump once, at a seeded random time, by a step of the
//! given size in a seeded random direction; readings and true biases carry it from then on.

use glam::DVec3;
use serde::Serialize;

use super::items::{PerSensor, BIAS_STEP};
use crate::rng::RngKey;

/// The step is drawn in the middle of the IMU's span: an estimator has converged before it and
/// has time after it.
const SPAN_START: f64 = 0.1;
const SPAN_WIDTH: f64 = 0.8;

const PURPOSE_TIME: u32 = 0;
const PURPOSE_DIRECTION: u32 = 1;

/// What was drawn: samples stamped at or after `at_ns` (in the IMU's clock, before any jitter)
/// read `gyroscope` rad/s and `accelerometer` m/s² more, and so do their true biases.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BiasStep {
    pub at_ns: u64,
    pub gyroscope: [f64; 3],
    pub accelerometer: [f64; 3],
}

impl BiasStep {
    /// The step of `size` for an IMU stream from `first_ns` to `last_ns`.
    pub fn draw(size: PerSensor, first_ns: u64, last_ns: u64, seed: u64) -> Self {
        let u = RngKey::new(seed, BIAS_STEP, 0, PURPOSE_TIME).uniform_f64([0; 4]);
        let span = last_ns.saturating_sub(first_ns) as f64;
        let at_ns = first_ns + ((SPAN_START + SPAN_WIDTH * u) * span) as u64;
        let direction = |sensor: u32| {
            let key = RngKey::new(seed, BIAS_STEP, sensor, PURPOSE_DIRECTION);
            // Three normals point uniformly on the sphere; redraw the (measure-zero) zero vector.
            (0..)
                .map(|round| {
                    DVec3::from_array(std::array::from_fn(|axis| {
                        key.normal_f64([axis as u32, round, 0, 0])
                    }))
                })
                .find(|v| v.length() > 1e-9)
                .unwrap_or(DVec3::X)
                .normalize()
        };
        Self {
            at_ns,
            gyroscope: (direction(0) * size.gyroscope).to_array(),
            accelerometer: (direction(1) * size.accelerometer).to_array(),
        }
    }

    /// The step a sample or state stamped `t_ns` carries: all of it from `at_ns` on, else none.
    pub fn at(&self, t_ns: u64) -> (DVec3, DVec3) {
        if t_ns >= self.at_ns {
            (
                DVec3::from_array(self.gyroscope),
                DVec3::from_array(self.accelerometer),
            )
        } else {
            (DVec3::ZERO, DVec3::ZERO)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SIZE: PerSensor = PerSensor {
        gyroscope: 0.02,
        accelerometer: 0.3,
    };

    #[test]
    fn the_step_has_the_given_size_and_lands_in_the_middle_of_the_span() {
        for seed in 0..200 {
            let step = BiasStep::draw(SIZE, 1_000, 101_000, seed);
            assert!((DVec3::from_array(step.gyroscope).length() - 0.02).abs() < 1e-15);
            assert!((DVec3::from_array(step.accelerometer).length() - 0.3).abs() < 1e-14);
            assert!((11_000..=91_000).contains(&step.at_ns), "{}", step.at_ns);
            assert_eq!(step.at(step.at_ns - 1), (DVec3::ZERO, DVec3::ZERO));
            assert_eq!(step.at(step.at_ns).0, DVec3::from_array(step.gyroscope));
        }
        assert_eq!(
            BiasStep::draw(SIZE, 0, 10, 3),
            BiasStep::draw(SIZE, 0, 10, 3)
        );
    }

    /// Times uniform over the middle 80 % (deciles within 5 binomial σ), directions isotropic
    /// (each component's mean 0 and mean square 1/3).
    #[test]
    fn times_are_uniform_and_directions_isotropic() {
        const N: u64 = 20_000;
        let mut deciles = [0u32; 10];
        let (mut mean, mut square) = (DVec3::ZERO, DVec3::ZERO);
        for seed in 0..N {
            let step = BiasStep::draw(SIZE, 0, 1_000_000_000, seed);
            let fraction = (step.at_ns as f64 / 1e9 - SPAN_START) / SPAN_WIDTH;
            deciles[((fraction * 10.0) as usize).min(9)] += 1;
            let d = DVec3::from_array(step.accelerometer) / 0.3;
            mean += d;
            square += d * d;
        }
        let expected = N as f64 / 10.0;
        for (i, &c) in deciles.iter().enumerate() {
            assert!(
                (c as f64 - expected).abs() < 5.0 * (expected * 0.9).sqrt(),
                "decile {i}: {c}"
            );
        }
        let n = N as f64;
        // A component of a uniform unit vector has variance 1/3: 5 σ of the mean is 0.02.
        assert!((mean / n).abs().max_element() < 0.02, "{:?}", mean / n);
        assert!(
            ((square / n) - DVec3::splat(1.0 / 3.0)).abs().max_element() < 0.02,
            "{:?}",
            square / n
        );
    }
}
