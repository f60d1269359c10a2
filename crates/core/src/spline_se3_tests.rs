use glam::DQuat;

use super::*;
use crate::test_motion::{hand_held_pose, hand_held_trajectory, rotation_angle};

/// Finite-difference steps (seconds): first differences, and second differences of positions.
const STEP: f64 = 1e-4;
const SECOND_DIFFERENCE_STEP: f64 = 1e-3;
/// Truncation (h² · jerk / 6 and the like) plus rounding of the central differences.
const VELOCITY_TOLERANCE: f64 = 1e-7;
const ACCELERATION_TOLERANCE: f64 = 1e-5;
/// Analytic results of closed-form cases and values on both sides of a knot.
const EXACT_TOLERANCE: f64 = 1e-9;

fn spline() -> SplineSe3 {
    SplineSe3::from_trajectory(&hand_held_trajectory(3.0, 12.0)).unwrap()
}

fn at(s: &SplineSe3, t: f64) -> SplineState {
    s.evaluate(t).unwrap()
}

/// Times inside the valid range, off the knots.
fn probe_times(s: &SplineSe3) -> Vec<f64> {
    let r = s.valid_range();
    (0..20)
        .map(|k| r.start + 0.013 + k as f64 * 0.53)
        .take_while(|&t| t + SECOND_DIFFERENCE_STEP < r.end)
        .collect()
}

fn assert_close(what: &str, t: f64, actual: DVec3, expected: DVec3, tolerance: f64) {
    let error = (actual - expected).length();
    assert!(
        error < tolerance,
        "{what} at t = {t}: {actual} vs {expected} (error {error:e})"
    );
}

#[test]
fn derivatives_match_central_differences_of_the_pose() {
    let s = spline();
    let times = probe_times(&s);
    assert!(times.len() >= 15, "{} probes", times.len());
    for t in times {
        let x = at(&s, t);
        let (before, after) = (at(&s, t - STEP), at(&s, t + STEP));
        let p = |y: &SplineState| y.world_from_body.translation;
        let velocity = (p(&after) - p(&before)) / (2.0 * STEP);
        assert_close(
            "velocity",
            t,
            x.linear_velocity_world,
            velocity,
            VELOCITY_TOLERANCE,
        );

        let (far_before, far_after) = (
            at(&s, t - SECOND_DIFFERENCE_STEP),
            at(&s, t + SECOND_DIFFERENCE_STEP),
        );
        let acceleration = (p(&far_after) - 2.0 * p(&x) + p(&far_before))
            / (SECOND_DIFFERENCE_STEP * SECOND_DIFFERENCE_STEP);
        let a = x.linear_acceleration_world;
        assert_close("acceleration", t, a, acceleration, ACCELERATION_TOLERANCE);

        // R(t−h)ᵀ R(t+h) = exp(2h ω_B + O(h³)).
        let turn = before.world_from_body.rotation.inverse() * after.world_from_body.rotation;
        let omega = turn.to_scaled_axis() / (2.0 * STEP);
        let w = x.angular_velocity_body;
        assert_close("angular velocity", t, w, omega, VELOCITY_TOLERANCE);

        let alpha = (after.angular_velocity_body - before.angular_velocity_body) / (2.0 * STEP);
        let dw = x.angular_acceleration_body;
        assert_close("angular acceleration", t, dw, alpha, ACCELERATION_TOLERANCE);
    }
}

/// A screw (constant body twist ξ per second) sampled at 20 Hz: every factor of the cumulative
/// product turns about the same twist, the basis sums to 1 + u, and the spline is the screw
/// itself with its constant velocities.
#[test]
fn a_constant_velocity_screw_is_reproduced() {
    let xi = Twist {
        rotation: DVec3::new(0.2, -0.3, 0.4),
        translation: DVec3::new(0.3, 0.1, -0.2),
    };
    let (start, dt) = (2.0, 0.05);
    let origin = Pose::new(DQuat::from_rotation_x(0.5), DVec3::new(1.0, 2.0, 3.0));
    let truth = |t: f64| origin.compose(&se3::exp(&xi.scaled(t - start)));
    let control = (0..12).map(|k| truth(start + k as f64 * dt)).collect();
    let s = SplineSe3::from_control_poses(start, dt, control).unwrap();
    let r = s.valid_range();
    for k in 0..=40 {
        let t = r.start + (r.end - r.start) * k as f64 / 40.0;
        let x = at(&s, t);
        let expected = truth(t);
        let rotation = DMat3::from_quat(expected.rotation);
        assert_close(
            "position",
            t,
            x.world_from_body.translation,
            expected.translation,
            EXACT_TOLERANCE,
        );
        assert!(rotation_angle(x.world_from_body.rotation, expected.rotation) < EXACT_TOLERANCE);
        // Ṫ = T ξ̂: ω_B = ω, ṗ = R ρ, p̈ = R (ω × ρ).
        let (w, rho) = (xi.rotation, xi.translation);
        assert_close("ω_B", t, x.angular_velocity_body, w, EXACT_TOLERANCE);
        assert_close(
            "α_B",
            t,
            x.angular_acceleration_body,
            DVec3::ZERO,
            EXACT_TOLERANCE,
        );
        let v = x.linear_velocity_world;
        assert_close("velocity", t, v, rotation * rho, EXACT_TOLERANCE);
        let a = x.linear_acceleration_world;
        assert_close(
            "acceleration",
            t,
            a,
            rotation * w.cross(rho),
            EXACT_TOLERANCE,
        );
    }
}

/// End of one segment (u = 1) against the start of the next (u = 0): pose, velocities and
/// accelerations all agree (C²), on a trajectory whose increments all differ.
#[test]
fn pose_velocity_and_acceleration_are_continuous_across_knots() {
    let s = spline();
    let knots = s.control.len() - 3;
    for i in 2..=knots {
        let (end, next) = (
            s.segment_state(i - 1, 1.0, &Pose::IDENTITY),
            s.segment_state(i, 0.0, &Pose::IDENTITY),
        );
        let t = s.start_time + i as f64 * s.spacing;
        let pose = |y: &SplineState| y.world_from_body.translation;
        assert_close("position", t, pose(&end), pose(&next), EXACT_TOLERANCE);
        let turn = rotation_angle(end.world_from_body.rotation, next.world_from_body.rotation);
        assert!(
            turn < EXACT_TOLERANCE,
            "orientation jumps {turn} rad at {t}"
        );
        for (what, a, b) in [
            ("ω_B", end.angular_velocity_body, next.angular_velocity_body),
            (
                "α_B",
                end.angular_acceleration_body,
                next.angular_acceleration_body,
            ),
            (
                "velocity",
                end.linear_velocity_world,
                next.linear_velocity_world,
            ),
            (
                "acceleration",
                end.linear_acceleration_world,
                next.linear_acceleration_world,
            ),
        ] {
            assert_close(what, t, a, b, EXACT_TOLERANCE);
        }
        // The public evaluation at the knot time picks one of the two.
        let x = at(&s, t);
        assert_close("evaluate", t, pose(&x), pose(&next), EXACT_TOLERANCE);
    }
}

/// The spline approximates: at a knot it is near, not on, the control pose (20 Hz hand-held
/// poses: within a millimetre and a tenth of a degree).
#[test]
fn the_spline_passes_near_its_control_poses() {
    const NEAR_METRES: f64 = 1e-3;
    const NEAR_RADIANS: f64 = 0.1 * std::f64::consts::PI / 180.0;
    let s = spline();
    let mut largest = 0.0_f64;
    for k in 1..s.control.len() - 1 {
        let t = s.start_time + k as f64 * s.spacing;
        let x = at(&s, t).world_from_body;
        let truth = hand_held_pose(t);
        let off = x.translation.distance(truth.translation);
        largest = largest.max(off);
        assert!(off < NEAR_METRES, "{off} m at {t}");
        assert!(rotation_angle(x.rotation, truth.rotation) < NEAR_RADIANS);
    }
    assert!(largest > 1e-7, "the spline should not interpolate exactly");
}

/// An attached frame's state is the body state moved by the rigid-body formulas: rotated rates,
/// v + ω × r and a + α × r + ω × (ω × r) for the lever arm r.
#[test]
fn an_attached_frame_gets_the_lever_arm_terms() {
    let s = spline();
    let body_from_frame = Pose::new(
        DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.2, 1.0),
        DVec3::new(0.1, -0.05, 0.2),
    );
    let r_bf = DMat3::from_quat(body_from_frame.rotation);
    for t in probe_times(&s) {
        let body = at(&s, t);
        let frame = s.evaluate_frame(t, &body_from_frame).unwrap();
        let r_wb = DMat3::from_quat(body.world_from_body.rotation);
        let (w, dw) = (body.angular_velocity_body, body.angular_acceleration_body);
        let r = body_from_frame.translation;
        let expected_pose = body.world_from_body.compose(&body_from_frame);
        let moved = |y: &SplineState| y.world_from_body.translation;
        assert_close(
            "pose",
            t,
            moved(&frame),
            expected_pose.translation,
            EXACT_TOLERANCE,
        );
        assert_close(
            "ω",
            t,
            frame.angular_velocity_body,
            r_bf.transpose() * w,
            EXACT_TOLERANCE,
        );
        let v = body.linear_velocity_world + r_wb * w.cross(r);
        assert_close("v", t, frame.linear_velocity_world, v, EXACT_TOLERANCE);
        let a = body.linear_acceleration_world + r_wb * (dw.cross(r) + w.cross(w.cross(r)));
        assert_close("a", t, frame.linear_acceleration_world, a, EXACT_TOLERANCE);
    }
}

/// Poses at uneven times along a screw are resampled onto the screw itself.
#[test]
fn uneven_timestamps_are_resampled_at_the_mean_spacing() {
    let xi = Twist {
        rotation: DVec3::new(0.0, 0.0, 0.5),
        translation: DVec3::new(0.3, 0.0, 0.1),
    };
    let truth = |t: f64| se3::exp(&xi.scaled(t));
    let times: Vec<f64> = (0..30)
        .map(|i| i as f64 * 0.05 + if i % 3 == 1 { 0.012 } else { 0.0 })
        .collect();
    let trajectory = Trajectory::new(times.clone(), times.iter().map(|&t| truth(t)).collect());
    let s = SplineSe3::from_trajectory(&trajectory).unwrap();
    assert!((s.spacing() - times[29] / 29.0).abs() < 1e-15);
    for t in [0.1, 0.333, 1.0, 1.3] {
        let x = at(&s, t);
        assert_close(
            "position",
            t,
            x.world_from_body.translation,
            truth(t).translation,
            1e-9,
        );
    }
}

#[test]
fn bad_input_is_an_error_value() {
    let s = spline();
    let r = s.valid_range();
    for t in [r.start - 1e-6, r.end + 1e-6, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(s.evaluate(t), Err(CoreError::TimeOutOfRange { .. })),
            "t = {t}"
        );
    }
    assert!(s.evaluate(r.start).is_ok() && s.evaluate(r.end).is_ok());

    let three = hand_held_trajectory(0.0, 0.1);
    assert_eq!(three.len(), 3);
    assert!(matches!(
        SplineSe3::from_trajectory(&three),
        Err(CoreError::SplineTooShort { poses: 3 })
    ));
    let mut unordered = hand_held_trajectory(0.0, 1.0);
    unordered.timestamps[5] = unordered.timestamps[4];
    assert!(matches!(
        SplineSe3::from_trajectory(&unordered),
        Err(CoreError::BadTimestamp { index: 5, .. })
    ));
    let mut ragged = hand_held_trajectory(0.0, 1.0);
    ragged.timestamps.pop();
    assert!(matches!(
        SplineSe3::from_trajectory(&ragged),
        Err(CoreError::TrajectoryLengths { .. })
    ));
    let poses = hand_held_trajectory(0.0, 1.0).poses;
    for spacing in [0.0, -0.05, f64::NAN] {
        assert!(matches!(
            SplineSe3::from_control_poses(0.0, spacing, poses.clone()),
            Err(CoreError::BadSplineSpacing { .. })
        ));
    }
}
