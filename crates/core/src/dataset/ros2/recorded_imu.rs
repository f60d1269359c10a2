//! The IMU topics of a recorded bag (`sensor_msgs/msg/Imu`), kept whole while the bag is read so
//! that the spec's IMU items can be applied to their readings: each message written back is the
//! recorded one with only its readings (and, under jitter, its stamp) changed; its orientation,
//! covariances and frame stay as recorded.

use super::bag::LogTimes;
use super::messages::{Imu, Time, Vector3};
use super::recorded_camera::median_rate;
use crate::dataset::euroc::ImuSample;
use crate::imu::ImuNoise;

pub const IMU_TYPE: &str = "sensor_msgs/msg/Imu";

/// An IMU topic: its index among the bag's topics, and its messages in file order.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordedImu {
    pub index: usize,
    pub name: String,
    pub messages: Vec<(Imu, LogTimes)>,
}

impl RecordedImu {
    /// The readings at their stamps, which must rise and not lie before 0 s.
    pub fn samples(&self) -> Result<Vec<ImuSample>, String> {
        let mut samples: Vec<ImuSample> = Vec::with_capacity(self.messages.len());
        for (message, _) in &self.messages {
            let stamp = message.header.stamp;
            let t_ns = u64::try_from(stamp.signed_nanoseconds()).map_err(|_| {
                format!(
                    "{}: a message stamped {:.9} s, before 0 s",
                    self.name,
                    stamp.seconds()
                )
            })?;
            if let Some(last) = samples.last().filter(|last| t_ns <= last.t_ns) {
                return Err(format!(
                    "{}: the message stamped {:.9} s follows one stamped {:.9} s; expected rising stamps",
                    self.name,
                    stamp.seconds(),
                    last.t_ns as f64 * 1e-9
                ));
            }
            samples.push(ImuSample {
                t_ns,
                gyro: vector(&message.angular_velocity),
                accel: vector(&message.linear_acceleration),
            });
        }
        Ok(samples)
    }

    /// The median rate of its stamps.
    pub fn rate_hz(&self) -> Result<f64, String> {
        let stamps: Vec<f64> = self
            .messages
            .iter()
            .map(|(m, _)| m.header.stamp.seconds())
            .collect();
        median_rate(&self.name, &stamps)
    }

    /// The noise densities its first message's covariances state (a reading's variance `σ² f`
    /// at `rate_hz`, Kalibr's convention, as rslam writes them), the mean of the three axes;
    /// no random walk, which a message does not carry. `None` when the covariances are unknown
    /// (all 0, REP 145) or not a variance.
    pub fn stated_noise(&self, rate_hz: f64) -> Option<ImuNoise> {
        let (first, _) = self.messages.first()?;
        let density = |covariance: &[f64; 9]| {
            let variance = (covariance[0] + covariance[4] + covariance[8]) / 3.0;
            (variance > 0.0 && variance.is_finite()).then(|| (variance / rate_hz).sqrt())
        };
        Some(ImuNoise {
            gyroscope_noise_density: density(&first.angular_velocity_covariance)?,
            gyroscope_random_walk: 0.0,
            accelerometer_noise_density: density(&first.linear_acceleration_covariance)?,
            accelerometer_random_walk: 0.0,
        })
    }

    /// Recorded message `input` carrying `sample`: its readings, and its stamp with the log and
    /// publish times moved by as much.
    pub fn rewritten(&self, input: usize, sample: &ImuSample) -> (Imu, LogTimes) {
        let (recorded, times) = &self.messages[input];
        let stamp = Time::from_nanoseconds(sample.t_ns as i64);
        let moved = stamp.signed_nanoseconds() - recorded.header.stamp.signed_nanoseconds();
        let mut message = recorded.clone();
        message.header.stamp = stamp;
        message.angular_velocity = message_vector(sample.gyro);
        message.linear_acceleration = message_vector(sample.accel);
        let times = LogTimes {
            log_time: times.log_time.saturating_add_signed(moved),
            publish_time: times.publish_time.saturating_add_signed(moved),
            sequence: times.sequence,
        };
        (message, times)
    }
}

fn vector(v: &Vector3) -> glam::DVec3 {
    glam::DVec3::new(v.x, v.y, v.z)
}

fn message_vector(v: glam::DVec3) -> Vector3 {
    Vector3 {
        x: v.x,
        y: v.y,
        z: v.z,
    }
}

#[cfg(test)]
mod tests {
    use super::super::messages::{Header, Quaternion};
    use super::*;

    fn message(t_ns: i64, variance: f64) -> (Imu, LogTimes) {
        let diagonal = [variance, 0.0, 0.0, 0.0, variance, 0.0, 0.0, 0.0, variance];
        let v = Vector3 {
            x: 0.1,
            y: 0.2,
            z: 9.8,
        };
        let imu = Imu {
            header: Header {
                stamp: Time::from_nanoseconds(t_ns),
                frame_id: "imu_link".into(),
            },
            orientation: Quaternion {
                x: 0.0,
                y: 0.0,
                z: 0.0,
                w: 1.0,
            },
            orientation_covariance: [0.01; 9],
            angular_velocity: v,
            angular_velocity_covariance: diagonal,
            linear_acceleration: v,
            linear_acceleration_covariance: diagonal,
        };
        let times = LogTimes {
            log_time: t_ns.max(0) as u64 + 1000,
            publish_time: t_ns.max(0) as u64 + 500,
            sequence: 7,
        };
        (imu, times)
    }

    fn topic(messages: Vec<(Imu, LogTimes)>) -> RecordedImu {
        RecordedImu {
            index: 3,
            name: "/imu/data".into(),
            messages,
        }
    }

    #[test]
    fn the_covariances_state_the_density_kalibr_would() {
        // σ = 1.7e-4 rad/s/√Hz at 200 Hz is a reading's variance σ² · 200.
        let sigma: f64 = 1.7e-4;
        let imu = topic(vec![message(0, sigma * sigma * 200.0)]);
        let noise = imu.stated_noise(200.0).unwrap();
        assert!((noise.gyroscope_noise_density - sigma).abs() < 1e-15);
        assert_eq!(noise.gyroscope_random_walk, 0.0);
        assert_eq!(topic(vec![message(0, 0.0)]).stated_noise(200.0), None);
    }

    #[test]
    fn a_rewritten_message_keeps_all_but_its_readings_and_moves_its_times_with_its_stamp() {
        let imu = topic(vec![message(5_000_000, 1e-6)]);
        let sample = ImuSample {
            t_ns: 5_000_300,
            gyro: glam::DVec3::new(1.0, 2.0, 3.0),
            accel: glam::DVec3::new(4.0, 5.0, 6.0),
        };
        let (written, times) = imu.rewritten(0, &sample);
        let (recorded, recorded_times) = &imu.messages[0];
        assert_eq!(written.header.stamp, Time::from_nanoseconds(5_000_300));
        assert_eq!(written.header.frame_id, recorded.header.frame_id);
        assert_eq!(
            written.orientation_covariance,
            recorded.orientation_covariance
        );
        assert_eq!(written.angular_velocity.z, 3.0);
        assert_eq!(written.linear_acceleration.x, 4.0);
        assert_eq!(times.log_time, recorded_times.log_time + 300);
        assert_eq!(times.publish_time, recorded_times.publish_time + 300);
        assert_eq!(times.sequence, 7);
    }

    #[test]
    fn stamps_must_rise_and_not_precede_zero() {
        let falling = topic(vec![message(10, 1e-6), message(10, 1e-6)]);
        assert!(falling
            .samples()
            .unwrap_err()
            .contains("expected rising stamps"));
        let negative = topic(vec![message(-5, 1e-6)]);
        assert!(negative.samples().unwrap_err().contains("before 0 s"));
    }
}
