//! Noise-free IMU readings synthesised along room0's default camera path (2000 poses at 20 Hz)
//! dead-reckon back onto the path: 1 s windows from the spline's state at their start end within
//! 1 mm and 0.01° of the spline (the IMU consistency bar of issue 20), for an IMU at the camera
//! and one a few centimetres off it.

use glam::{DQuat, DVec3, EulerRot};
use rslam_core::imu::{
    dead_reckon, synthesize_imu, ImuNoise, ImuSynthesis, InertialState, GRAVITY_WORLD,
};
use rslam_core::{Pose, SplineSe3};
use rslam_render::load_scene;

const POSITION_TOLERANCE_M: f64 = 1e-3;
const ORIENTATION_TOLERANCE_DEG: f64 = 0.01;
const RATE_HZ: f64 = 200.0;
const SAMPLES_PER_WINDOW: usize = 200;

/// The angle between two orientations, accurate near zero.
fn rotation_angle(a: DQuat, b: DQuat) -> f64 {
    let d = a.inverse() * b;
    2.0 * d.xyz().length().atan2(d.w.abs())
}

#[test]
fn noise_free_imu_on_room0_dead_reckons_onto_the_path() {
    let scene = load_scene("room0").unwrap();
    let trajectory = scene.default_trajectory.unwrap();
    let spline = SplineSe3::from_trajectory(&trajectory).unwrap();
    let rig = Pose::new(
        DQuat::from_euler(EulerRot::XYZ, -0.5 * std::f64::consts::PI, 0.1, 0.05),
        DVec3::new(0.06, -0.02, 0.03),
    );
    for (name, body_from_imu) in [("camera", Pose::IDENTITY), ("rig", rig)] {
        let options = ImuSynthesis {
            rate_hz: RATE_HZ,
            body_from_imu,
            noise: ImuNoise::ZERO,
            ..ImuSynthesis::default()
        };
        let samples = synthesize_imu(&spline, &options).unwrap();
        let (mut worst_m, mut worst_deg, mut windows) = (0.0_f64, 0.0_f64, 0);
        let (mut fastest, mut fastest_turn) = (0.0_f64, 0.0_f64);
        for window in samples
            .windows(SAMPLES_PER_WINDOW + 1)
            .step_by(SAMPLES_PER_WINDOW)
        {
            let at = |t| spline.evaluate_frame(t, &body_from_imu).unwrap();
            let start = at(window[0].timestamp);
            let end = at(window[SAMPLES_PER_WINDOW].timestamp);
            let reckoned = dead_reckon(
                InertialState {
                    world_from_imu: start.world_from_body,
                    velocity_world: start.linear_velocity_world,
                },
                window,
                GRAVITY_WORLD,
            );
            let truth = end.world_from_body;
            worst_m = worst_m.max(
                reckoned
                    .world_from_imu
                    .translation
                    .distance(truth.translation),
            );
            let turn = rotation_angle(reckoned.world_from_imu.rotation, truth.rotation);
            worst_deg = worst_deg.max(turn.to_degrees());
            for s in window {
                fastest_turn = fastest_turn.max(s.truth.gyroscope.length().to_degrees());
            }
            fastest = fastest.max(start.linear_velocity_world.length());
            windows += 1;
        }
        eprintln!(
            "room0, IMU at {name}: {windows} windows of 1 s, worst position {worst_m:.3e} m, \
             worst orientation {worst_deg:.3e}° (speeds up to {fastest:.2} m/s, turns up to \
             {fastest_turn:.0}°/s)"
        );
        assert!(windows >= 95, "{windows} windows");
        assert!(worst_m < POSITION_TOLERANCE_M, "IMU at {name}: {worst_m} m");
        assert!(
            worst_deg < ORIENTATION_TOLERANCE_DEG,
            "IMU at {name}: {worst_deg}°"
        );
    }
}
