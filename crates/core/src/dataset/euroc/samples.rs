//! What the data.csv files of a EuRoC dataset hold, row by row: camera frames, IMU samples and
//! ground-truth states, each stamped in integer nanoseconds.

use std::path::PathBuf;

use glam::DVec3;

use crate::Pose;

const NANOSECONDS_PER_SECOND: f64 = 1e9;

/// `seconds` as integer nanoseconds, rounded; `None` when it is not finite, negative or past
/// `u64::MAX` ns (year 2554).
pub fn nanoseconds_from_seconds(seconds: f64) -> Option<u64> {
    let ns = (seconds * NANOSECONDS_PER_SECOND).round();
    // u64::MAX as f64 rounds up to 2^64, which does not fit: refuse it and above.
    (ns.is_finite() && ns >= 0.0 && ns < u64::MAX as f64).then_some(ns as u64)
}

/// One camera frame: its capture time and its image file (`mav0/camN/data/<t_ns>.png`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EurocFrame {
    pub t_ns: u64,
    pub path: PathBuf,
}

/// One line of `imu0/data.csv`: angular rate `w_RS_S` (rad/s) and specific force `a_RS_S`
/// (m/s²), both in the IMU frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImuSample {
    pub t_ns: u64,
    pub gyro: DVec3,
    pub accel: DVec3,
}

/// One line of `state_groundtruth_estimate0/data.csv`: the body pose in the world (`p_RS_R`,
/// `q_RS`), its velocity in the world (`v_RS_R`) and the IMU biases (`b_w_RS_S`, `b_a_RS_S`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroundTruthState {
    pub t_ns: u64,
    pub world_from_body: Pose,
    /// m/s, world frame.
    pub velocity: DVec3,
    /// rad/s
    pub gyro_bias: DVec3,
    /// m/s²
    pub accel_bias: DVec3,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seconds_round_to_the_nearest_nanosecond() {
        assert_eq!(nanoseconds_from_seconds(0.0), Some(0));
        assert_eq!(nanoseconds_from_seconds(1.5), Some(1_500_000_000));
        assert_eq!(nanoseconds_from_seconds(0.05), Some(50_000_000));
        assert_eq!(nanoseconds_from_seconds(1e-9 * 0.6), Some(1));
        // f64 near 1.4e9 s resolves about 240 ns; the result is the nearest nanosecond of it.
        let t = nanoseconds_from_seconds(1_403_636_579.763_555_5).unwrap();
        assert!(t.abs_diff(1_403_636_579_763_555_500) < 500, "{t}");
        for bad in [-1.0, f64::NAN, f64::INFINITY, 1e11] {
            assert_eq!(nanoseconds_from_seconds(bad), None, "{bad}");
        }
    }
}
