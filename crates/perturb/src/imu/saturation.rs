//! `imu_saturation:GYRO/ACC`: every axis of every reading clipped to the sensor's range, as a
//! real sensor's output stops at the end of its range.

use glam::DVec3;
use rslam_core::dataset::euroc::ImuSample;
use serde::Serialize;

use super::items::PerSensor;

/// How many samples had at least one axis clipped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Saturated {
    pub gyroscope_samples: usize,
    pub accelerometer_samples: usize,
}

fn clip(v: DVec3, range: f64) -> (DVec3, bool) {
    let clipped = v.clamp(DVec3::splat(-range), DVec3::splat(range));
    (clipped, clipped != v)
}

pub fn saturate(samples: &mut [ImuSample], range: PerSensor) -> Saturated {
    let mut count = Saturated::default();
    for s in samples {
        let (gyro, g) = clip(s.gyro, range.gyroscope);
        let (accel, a) = clip(s.accel, range.accelerometer);
        s.gyro = gyro;
        s.accel = accel;
        count.gyroscope_samples += usize::from(g);
        count.accelerometer_samples += usize::from(a);
    }
    count
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn readings_beyond_the_range_are_clipped_exactly_and_the_rest_kept() {
        let sample = |g: [f64; 3], a: [f64; 3]| ImuSample {
            t_ns: 0,
            gyro: DVec3::from_array(g),
            accel: DVec3::from_array(a),
        };
        let mut samples = vec![
            sample([0.5, -2.5, 2.0], [9.81, 0.0, -40.0]),
            sample([1.999, -1.0, 0.0], [39.9, -39.9, 0.1]),
        ];
        let range = PerSensor {
            gyroscope: 2.0,
            accelerometer: 39.2,
        };
        let count = saturate(&mut samples, range);
        assert_eq!(samples[0].gyro, DVec3::new(0.5, -2.0, 2.0));
        assert_eq!(samples[0].accel, DVec3::new(9.81, 0.0, -39.2));
        assert_eq!(samples[1].gyro, DVec3::new(1.999, -1.0, 0.0));
        assert_eq!(samples[1].accel, DVec3::new(39.2, -39.2, 0.1));
        assert_eq!(
            count,
            Saturated {
                gyroscope_samples: 1,
                accelerometer_samples: 2
            }
        );
    }
}
