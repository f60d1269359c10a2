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
#[path = "spline_se3_tests.rs"]
mod tests;
