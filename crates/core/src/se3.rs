//! Rigid motion as a twist: the exponential and logarithm of SE(3), and poses between (or just
//! beyond) the samples of a path at constant velocity — the camera's pose at any instant of an
//! exposure or a rolling-shutter read-out.

use glam::{DMat3, DQuat, DVec3};

use crate::Pose;

/// Below this rotation angle (radians) the series forms of the SE(3) Jacobian are used.
const SMALL_ANGLE: f64 = 1e-6;

/// An element of se(3): `rotation` is the axis times the angle (radians), `translation` the
/// translational part ρ with `t = V(rotation) ρ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Twist {
    pub rotation: DVec3,
    pub translation: DVec3,
}

impl Twist {
    pub fn scaled(&self, s: f64) -> Twist {
        Twist {
            rotation: self.rotation * s,
            translation: self.translation * s,
        }
    }
}

/// V(ω) = I + (1 − cos θ)/θ² [ω]× + (θ − sin θ)/θ³ [ω]×² (Barfoot, State Estimation, eq. 7.86).
fn left_jacobian(omega: DVec3) -> DMat3 {
    let theta = omega.length();
    let k = skew(omega);
    let (a, b) = if theta < SMALL_ANGLE {
        (0.5, 1.0 / 6.0)
    } else {
        let t2 = theta * theta;
        (
            (1.0 - theta.cos()) / t2,
            (theta - theta.sin()) / (t2 * theta),
        )
    };
    DMat3::IDENTITY + k * a + k * k * b
}

/// The cross-product matrix `[v]×`: `skew(v) * w == v.cross(w)`.
pub(crate) fn skew(v: DVec3) -> DMat3 {
    DMat3::from_cols(
        DVec3::new(0.0, v.z, -v.y),
        DVec3::new(-v.z, 0.0, v.x),
        DVec3::new(v.y, -v.x, 0.0),
    )
}

/// The pose `exp(ξ)`.
pub fn exp(xi: &Twist) -> Pose {
    let rotation = DQuat::from_scaled_axis(xi.rotation);
    Pose::new(rotation, left_jacobian(xi.rotation) * xi.translation)
}

/// The twist ξ with `exp(ξ) = pose`, rotation angle in [0, π].
pub fn log(pose: &Pose) -> Twist {
    let mut q = pose.rotation.normalize();
    if q.w < 0.0 {
        q = -q;
    }
    let omega = q.to_scaled_axis();
    Twist {
        rotation: omega,
        translation: left_jacobian(omega).inverse() * pose.translation,
    }
}

impl Pose {
    /// The pose a fraction `alpha` of the way from `self` to `other` at constant body velocity
    /// (geodesic on SE(3)): `self · exp(alpha · log(self⁻¹ · other))`. `alpha` outside [0, 1]
    /// extrapolates the same motion.
    pub fn interpolate(&self, other: &Pose, alpha: f64) -> Pose {
        let motion = log(&self.inverse().compose(other));
        self.compose(&exp(&motion.scaled(alpha)))
    }
}

/// The pose at fractional sample `u` of a path sampled at equal intervals: between samples
/// ⌊u⌋ and ⌊u⌋ + 1, and before the first or after the last sample the motion of the nearest
/// interval continued. A path of one pose stands still.
pub fn pose_along(poses: &[Pose], u: f64) -> Pose {
    match poses {
        [] => Pose::IDENTITY,
        [only] => *only,
        _ => {
            let i = (u.floor().max(0.0) as usize).min(poses.len() - 2);
            poses[i].interpolate(&poses[i + 1], u - i as f64)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOLERANCE: f64 = 1e-10;

    fn close(a: &Pose, b: &Pose) -> bool {
        a.translation.distance(b.translation) < TOLERANCE
            && a.rotation.dot(b.rotation).abs() > 1.0 - TOLERANCE
    }

    fn sample() -> Pose {
        Pose::new(
            DQuat::from_scaled_axis(DVec3::new(0.3, -1.1, 0.7)),
            DVec3::new(1.0, -2.0, 0.5),
        )
    }

    #[test]
    fn exp_inverts_log() {
        for pose in [sample(), Pose::IDENTITY, sample().inverse()] {
            assert!(close(&exp(&log(&pose)), &pose), "{pose:?}");
        }
        let tiny = Pose::new(
            DQuat::from_scaled_axis(DVec3::new(1e-9, 0.0, 0.0)),
            DVec3::X,
        );
        assert!(close(&exp(&log(&tiny)), &tiny));
    }

    #[test]
    fn interpolation_hits_both_ends_and_halves_the_motion() {
        let (a, b) = (sample(), sample().compose(&sample()));
        assert!(close(&a.interpolate(&b, 0.0), &a));
        assert!(close(&a.interpolate(&b, 1.0), &b));
        let mid = a.interpolate(&b, 0.5);
        let first_half = mid.inverse().compose(&b);
        let second_half = a.inverse().compose(&mid);
        assert!(close(&first_half, &second_half), "equal halves");
    }

    /// A screw motion (constant rotation rate about an axis while moving along it) is
    /// sampled exactly, between and beyond the samples.
    #[test]
    fn pose_along_follows_a_constant_velocity_path() {
        let xi = Twist {
            rotation: DVec3::new(0.0, 0.2, 0.0),
            translation: DVec3::new(0.1, 0.0, 0.3),
        };
        let at = |s: f64| exp(&xi.scaled(s));
        let path: Vec<Pose> = (0..4).map(|i| at(i as f64)).collect();
        for u in [0.0, 0.25, 1.5, 2.999, 3.0, -0.5, 3.4] {
            assert!(close(&pose_along(&path, u), &at(u)), "u = {u}");
        }
        assert!(close(&pose_along(&path[..1], 2.5), &path[0]));
    }
}
