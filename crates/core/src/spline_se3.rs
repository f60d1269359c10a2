//! A C²-continuous cubic B-spline on SE(3) in cumulative form, the continuous-time motion that
//! IMU readings are drawn from.
//!
//! Control poses `T_k` are spaced uniformly in time, `Δ` apart. Between control times `t_i` and
//! `t_{i+1}`, with `u = (t − t_i) / Δ ∈ [0, 1]`,
//!
//! ```text
//! T(u) = T_{i−1} · exp(B₁(u) Ω_i) · exp(B₂(u) Ω_{i+1}) · exp(B₃(u) Ω_{i+2}),
//! Ω_k = log(T_{k−1}⁻¹ T_k),
//! B₁ = (5 + 3u − 3u² + u³)/6,  B₂ = (1 + 3u + 3u² − 2u³)/6,  B₃ = u³/6
//! ```
//!
//! (Lovegrove, Patron-Perez & Sibley, "Spline Fusion", BMVC 2013, eqs. 4–6; Mueller, Sommer et al.
//! name it the cumulative form). This is the spline of OpenVINS' `ov_core::BsplineSE3`: like it,
//! the spline *approximates* the control poses rather than passing through them (at a knot it sits
//! at a weighted mean of three neighbours), it is valid from the second control time to the
//! second-to-last, and a trajectory's poses are resampled at their mean spacing to become the
//! control poses. Velocities and accelerations are analytic derivatives of the product above
//! (its factors' derivatives are `d/du exp(B Ω̂) = exp(B Ω̂) Ω̂ B'`), not finite differences.

use glam::{DMat3, DMat4, DVec3};

use crate::se3::{self, skew, Twist};
use crate::{CoreError, Pose, Trajectory};

/// A cubic B-spline on SE(3) through uniformly spaced control poses `world_from_body`.
#[derive(Clone, Debug)]
pub struct SplineSe3 {
    /// Time of control pose 0, seconds.
    start_time: f64,
    /// Seconds between control poses.
    spacing: f64,
    control: Vec<Pose>,
    /// `increments[k] = log(control[k]⁻¹ · control[k + 1])`.
    increments: Vec<Twist>,
}

/// Times (seconds) at which the spline may be evaluated, both ends included.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeRange {
    pub start: f64,
    pub end: f64,
}

/// The motion of the body (or of a frame rigidly attached to it, see
/// [`SplineSe3::evaluate_frame`]) at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplineState {
    pub world_from_body: Pose,
    /// ω_B with `Ṙ_WB = R_WB [ω_B]×`, rad/s.
    pub angular_velocity_body: DVec3,
    /// dω_B/dt, rad/s².
    pub angular_acceleration_body: DVec3,
    /// d/dt of the body origin in the world frame, m/s.
    pub linear_velocity_world: DVec3,
    /// d²/dt² of the body origin in the world frame, m/s² (gravity not included).
    pub linear_acceleration_world: DVec3,
}

/// The cumulative basis functions and their first and second derivatives in `u`.
struct CumulativeBasis {
    value: [f64; 3],
    first: [f64; 3],
    second: [f64; 3],
}

impl CumulativeBasis {
    fn at(u: f64) -> Self {
        let (u2, u3) = (u * u, u * u * u);
        Self {
            value: [
                (5.0 + 3.0 * u - 3.0 * u2 + u3) / 6.0,
                (1.0 + 3.0 * u + 3.0 * u2 - 2.0 * u3) / 6.0,
                u3 / 6.0,
            ],
            first: [
                (3.0 - 6.0 * u + 3.0 * u2) / 6.0,
                (3.0 + 6.0 * u - 6.0 * u2) / 6.0,
                0.5 * u2,
            ],
            second: [u - 1.0, 1.0 - 2.0 * u, u],
        }
    }
}

/// The 4×4 matrix `Ω̂ = [[ω]×, ρ; 0, 0]` of a twist, whose matrix exponential is `se3::exp`.
fn hat(xi: &Twist) -> DMat4 {
    let k = skew(xi.rotation);
    DMat4::from_cols(
        k.x_axis.extend(0.0),
        k.y_axis.extend(0.0),
        k.z_axis.extend(0.0),
        xi.translation.extend(0.0),
    )
}

/// The vector of the skew-symmetric part of `m` (the inverse of `skew` on skew matrices).
fn vee(m: DMat3) -> DVec3 {
    0.5 * DVec3::new(
        m.y_axis.z - m.z_axis.y,
        m.z_axis.x - m.x_axis.z,
        m.x_axis.y - m.y_axis.x,
    )
}

fn rotation_block(m: &DMat4) -> DMat3 {
    DMat3::from_mat4(*m)
}

impl SplineSe3 {
    /// The spline whose control pose `k` is `control[k]` at `start_time + k · spacing`.
    pub fn from_control_poses(
        start_time: f64,
        spacing: f64,
        control: Vec<Pose>,
    ) -> Result<Self, CoreError> {
        if control.len() < 4 {
            return Err(CoreError::SplineTooShort {
                poses: control.len(),
            });
        }
        if !start_time.is_finite() {
            return Err(CoreError::BadTimestamp {
                index: 0,
                time: start_time,
            });
        }
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(CoreError::BadSplineSpacing { spacing });
        }
        let increments = control
            .windows(2)
            .map(|w| se3::log(&w[0].inverse().compose(&w[1])))
            .collect();
        Ok(Self {
            start_time,
            spacing,
            control,
            increments,
        })
    }

    /// The spline of a trajectory, as OpenVINS builds it: control poses every mean pose spacing
    /// from the first timestamp, each the constant-velocity (SE(3) geodesic) interpolation of the
    /// two trajectory poses around its time. Poses at a uniform rate are used as they are.
    pub fn from_trajectory(trajectory: &Trajectory) -> Result<Self, CoreError> {
        let (times, poses) = (&trajectory.timestamps, &trajectory.poses);
        if times.len() != poses.len() {
            return Err(CoreError::TrajectoryLengths {
                timestamps: times.len(),
                poses: poses.len(),
            });
        }
        if poses.len() < 4 {
            return Err(CoreError::SplineTooShort { poses: poses.len() });
        }
        for (index, &time) in times.iter().enumerate() {
            if !time.is_finite() || (index > 0 && time <= times[index - 1]) {
                return Err(CoreError::BadTimestamp { index, time });
            }
        }
        let n = poses.len();
        let start = times[0];
        let spacing = (times[n - 1] - start) / (n - 1) as f64;
        let control = (0..n)
            .map(|k| {
                let t = start + k as f64 * spacing;
                let j = times.partition_point(|&s| s <= t).clamp(1, n - 1) - 1;
                let alpha = (t - times[j]) / (times[j + 1] - times[j]);
                poses[j].interpolate(&poses[j + 1], alpha)
            })
            .collect();
        Self::from_control_poses(start, spacing, control)
    }

    /// Seconds between control poses.
    pub fn spacing(&self) -> f64 {
        self.spacing
    }

    /// From the second control time to the second-to-last.
    pub fn valid_range(&self) -> TimeRange {
        TimeRange {
            start: self.start_time + self.spacing,
            end: self.start_time + (self.control.len() - 2) as f64 * self.spacing,
        }
    }

    /// The body's pose and motion at `t` (seconds).
    pub fn evaluate(&self, t: f64) -> Result<SplineState, CoreError> {
        self.evaluate_frame(t, &Pose::IDENTITY)
    }

    /// The pose and motion of a frame rigidly attached to the body, `body_from_frame` (an IMU
    /// at its extrinsic, say), at `t`: the spline right-multiplied by the constant transform, so
    /// `world_from_body` is `world_from_body ∘ body_from_frame`, the angular rates are in the
    /// frame's axes and the linear terms are those of the frame's origin (lever-arm terms
    /// included, exactly).
    pub fn evaluate_frame(&self, t: f64, body_from_frame: &Pose) -> Result<SplineState, CoreError> {
        let range = self.valid_range();
        // Written so that NaN is refused too.
        if !(t >= range.start && t <= range.end) {
            return Err(CoreError::TimeOutOfRange {
                time: t,
                start: range.start,
                end: range.end,
            });
        }
        let s = (t - self.start_time) / self.spacing;
        let segment = (s.floor() as usize).clamp(1, self.control.len() - 3);
        Ok(self.segment_state(segment, s - segment as f64, body_from_frame))
    }

    /// The state at fraction `u` of the way from control time `segment` to `segment + 1`.
    fn segment_state(&self, segment: usize, u: f64, body_from_frame: &Pose) -> SplineState {
        let basis = CumulativeBasis::at(u);
        let mut pose = self.control[segment - 1];
        let mut a = [DMat4::IDENTITY; 3];
        let mut da = [DMat4::ZERO; 3];
        let mut dda = [DMat4::ZERO; 3];
        for j in 0..3 {
            let omega = &self.increments[segment - 1 + j];
            let step = se3::exp(&omega.scaled(basis.value[j]));
            pose = pose.compose(&step);
            let h = hat(omega);
            a[j] = step.to_mat4();
            da[j] = a[j] * h * basis.first[j];
            dda[j] = a[j] * h * h * (basis.first[j] * basis.first[j]) + a[j] * h * basis.second[j];
        }
        let pose = pose.compose(body_from_frame);
        let (t0, f) = (
            self.control[segment - 1].to_mat4(),
            body_from_frame.to_mat4(),
        );
        let du = da[0] * a[1] * a[2] + a[0] * da[1] * a[2] + a[0] * a[1] * da[2];
        let ddu = dda[0] * a[1] * a[2]
            + a[0] * dda[1] * a[2]
            + a[0] * a[1] * dda[2]
            + (da[0] * da[1] * a[2] + da[0] * a[1] * da[2] + a[0] * da[1] * da[2]) * 2.0;
        let d = t0 * du * f * (1.0 / self.spacing);
        let dd = t0 * ddu * f * (1.0 / (self.spacing * self.spacing));
        let r_t = DMat3::from_quat(pose.rotation).transpose();
        SplineState {
            world_from_body: pose,
            angular_velocity_body: vee(r_t * rotation_block(&d)),
            // R^T R̈ = d/dt[ω]× − Ṙ^T Ṙ, and Ṙ^T Ṙ is symmetric.
            angular_acceleration_body: vee(r_t * rotation_block(&dd)),
            linear_velocity_world: d.w_axis.truncate(),
            linear_acceleration_world: dd.w_axis.truncate(),
        }
    }
}

#[cfg(test)]
mod tests {
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
            assert!(
                rotation_angle(x.world_from_body.rotation, expected.rotation) < EXACT_TOLERANCE
            );
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
}
