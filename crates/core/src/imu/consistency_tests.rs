//! Noise-free IMU readings dead-reckoned from a ground-truth state land on the spline's own pose;
//! samples carry their truth and biases, and a seed fixes the noise.

use glam::{DMat3, DQuat, DVec3, EulerRot};

use super::*;
use crate::test_motion::{hand_held_trajectory, rotation_angle};
use crate::{Pose, SplineSe3};

/// The bar for 1 s windows of noise-free readings.
const POSITION_TOLERANCE_M: f64 = 1e-3;
const ORIENTATION_TOLERANCE_DEG: f64 = 0.01;
const WINDOW_S: f64 = 1.0;
const RATE_HZ: f64 = 200.0;

/// A camera-to-IMU extrinsic like a hand-held rig's: a few centimetres off, axes turned.
fn rig_extrinsic() -> Pose {
    Pose::new(
        DQuat::from_euler(EulerRot::XYZ, -0.5 * std::f64::consts::PI, 0.1, 0.05),
        DVec3::new(0.06, -0.02, 0.03),
    )
}

struct WindowErrors {
    worst_position_m: f64,
    worst_orientation_deg: f64,
    windows: usize,
}

/// Dead-reckons each whole `WINDOW_S` window of noise-free samples (second order, see
/// [`dead_reckon`]) from the spline's state at its start and compares the end with the spline.
fn integrate_windows(spline: &SplineSe3, body_from_imu: Pose) -> WindowErrors {
    let options = ImuSynthesis {
        rate_hz: RATE_HZ,
        body_from_imu,
        noise: ImuNoise::ZERO,
        ..ImuSynthesis::default()
    };
    let samples = synthesize_imu(spline, &options).unwrap();
    let per_window = (WINDOW_S * RATE_HZ).round() as usize;
    let mut errors = WindowErrors {
        worst_position_m: 0.0,
        worst_orientation_deg: 0.0,
        windows: 0,
    };
    for window in samples.windows(per_window + 1).step_by(per_window) {
        let start = spline
            .evaluate_frame(window[0].timestamp, &body_from_imu)
            .unwrap();
        let start = InertialState {
            world_from_imu: start.world_from_body,
            velocity_world: start.linear_velocity_world,
        };
        let state = dead_reckon(start, window, GRAVITY_WORLD);
        let end = spline
            .evaluate_frame(window[per_window].timestamp, &body_from_imu)
            .unwrap();
        let position = (state.world_from_imu.translation).distance(end.world_from_body.translation);
        let orientation =
            rotation_angle(state.world_from_imu.rotation, end.world_from_body.rotation);
        errors.worst_position_m = errors.worst_position_m.max(position);
        errors.worst_orientation_deg = errors.worst_orientation_deg.max(orientation.to_degrees());
        errors.windows += 1;
    }
    errors
}

#[test]
fn noise_free_readings_integrate_back_to_the_trajectory() {
    let spline = SplineSe3::from_trajectory(&hand_held_trajectory(0.0, 30.0)).unwrap();
    for (name, extrinsic) in [("identity", Pose::IDENTITY), ("rig", rig_extrinsic())] {
        let e = integrate_windows(&spline, extrinsic);
        eprintln!(
            "{name}: {} windows of {WINDOW_S} s at {RATE_HZ} Hz: worst position {:.3e} m, \
             worst orientation {:.3e}°",
            e.windows, e.worst_position_m, e.worst_orientation_deg
        );
        assert!(e.windows >= 25, "{} windows", e.windows);
        assert!(e.worst_position_m < POSITION_TOLERANCE_M, "{name}");
        assert!(
            e.worst_orientation_deg < ORIENTATION_TOLERANCE_DEG,
            "{name}"
        );
    }
}

/// At rest the gyroscope reads 0 and the accelerometer +g up, in the IMU's own axes.
#[test]
fn a_still_imu_reads_gravity_upwards() {
    let pose = Pose::new(DQuat::from_rotation_y(0.3), DVec3::new(1.0, 2.0, 3.0));
    let spline = SplineSe3::from_control_poses(0.0, 0.05, vec![pose; 6]).unwrap();
    let extrinsic = rig_extrinsic();
    let reading = ideal_reading(&spline, 0.1, &extrinsic, GRAVITY_WORLD).unwrap();
    let imu_from_world = DMat3::from_quat(pose.rotation * extrinsic.rotation).transpose();
    assert!(reading.gyroscope.length() < 1e-12);
    let up = imu_from_world * DVec3::new(0.0, 0.0, 9.81);
    assert!(reading.accelerometer.distance(up) < 1e-12, "{reading:?}");
}

#[test]
fn samples_cover_the_valid_range_and_carry_truth_and_bias() {
    let spline = SplineSe3::from_trajectory(&hand_held_trajectory(5.0, 3.0)).unwrap();
    let bias = ImuBias {
        gyroscope: DVec3::new(0.01, -0.02, 0.03),
        accelerometer: DVec3::new(0.1, 0.2, -0.3),
    };
    let options = ImuSynthesis {
        noise: ImuNoise::ZERO,
        initial_bias: bias,
        ..ImuSynthesis::default()
    };
    let samples = synthesize_imu(&spline, &options).unwrap();
    let range = spline.valid_range();
    // 5.05 s to 7.95 s at 200 Hz, both ends included.
    assert_eq!(samples.len(), 581);
    assert_eq!(samples[0].timestamp, range.start);
    assert!((samples[580].timestamp - range.end).abs() < 1e-12);
    for s in &samples {
        assert_eq!(s.bias, bias);
        assert!((s.measured.gyroscope - s.truth.gyroscope - bias.gyroscope).length() < 1e-15);
        let accelerometer = s.measured.accelerometer - s.truth.accelerometer;
        assert!((accelerometer - bias.accelerometer).length() < 1e-12);
    }
}

#[test]
fn a_seed_fixes_the_noise() {
    let spline = SplineSe3::from_trajectory(&hand_held_trajectory(0.0, 2.0)).unwrap();
    let with_seed = |seed| {
        synthesize_imu(
            &spline,
            &ImuSynthesis {
                seed,
                ..ImuSynthesis::default()
            },
        )
        .unwrap()
    };
    let (a, b, c) = (with_seed(1), with_seed(1), with_seed(2));
    assert_eq!(a, b);
    assert_eq!(a.len(), c.len());
    for (x, y) in a.iter().zip(&c) {
        assert_eq!(x.truth, y.truth);
        assert_ne!(x.measured.gyroscope, y.measured.gyroscope);
        assert_ne!(x.measured.accelerometer, y.measured.accelerometer);
    }
    // Biases walk: the first sample has the initial bias, later ones have moved.
    assert_eq!(a[0].bias, ImuBias::default());
    assert_ne!(a[1].bias.gyroscope, DVec3::ZERO);
    assert_ne!(a[1].bias.gyroscope, c[1].bias.gyroscope);
}

#[test]
fn bad_options_are_error_values() {
    let spline = SplineSe3::from_trajectory(&hand_held_trajectory(0.0, 1.0)).unwrap();
    for rate_hz in [0.0, -200.0, f64::NAN, f64::INFINITY] {
        let options = ImuSynthesis {
            rate_hz,
            ..ImuSynthesis::default()
        };
        assert!(matches!(
            synthesize_imu(&spline, &options),
            Err(crate::CoreError::BadRate { .. })
        ));
    }
    let options = ImuSynthesis {
        rate_hz: 1e12,
        ..ImuSynthesis::default()
    };
    assert!(matches!(
        synthesize_imu(&spline, &options),
        Err(crate::CoreError::TooManyImuSamples { .. })
    ));
    let options = ImuSynthesis {
        noise: ImuNoise {
            gyroscope_noise_density: -1.0,
            ..ImuNoise::ZERO
        },
        ..ImuSynthesis::default()
    };
    assert!(matches!(
        synthesize_imu(&spline, &options),
        Err(crate::CoreError::BadImuNoise { .. })
    ));
}
