//! Relative pose error: for pose pairs (i, j) of the associated sequence,
//! E = (Q_i⁻¹ Q_j)⁻¹ (P_i⁻¹ P_j) with Q the ground truth and P the (aligned) estimate
//! (Sturm et al., "A benchmark for the evaluation of RGB-D SLAM systems", IROS 2012, eq. 2;
//! evo's `metrics.RPE`).

use std::fmt;
use std::str::FromStr;

use glam::DQuat;
use rslam_core::Pose;
use serde::Serialize;

use crate::rpe_pairs::pose_pairs;
use crate::EvalError;

/// The unit of the RPE step `delta`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub enum DeltaUnit {
    /// Poses of the associated sequence.
    #[default]
    #[serde(rename = "f")]
    Frames,
    /// Metres travelled along the estimate.
    #[serde(rename = "m")]
    Meters,
    /// Degrees turned by the estimate.
    #[serde(rename = "deg")]
    Degrees,
}

impl DeltaUnit {
    pub fn name(self) -> &'static str {
        match self {
            DeltaUnit::Frames => "f",
            DeltaUnit::Meters => "m",
            DeltaUnit::Degrees => "deg",
        }
    }

    /// evo's wording of the unit, for the report.
    pub fn long_name(self) -> &'static str {
        match self {
            DeltaUnit::Frames => "frames",
            DeltaUnit::Meters => "m",
            DeltaUnit::Degrees => "deg",
        }
    }
}

impl fmt::Display for DeltaUnit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for DeltaUnit {
    type Err = EvalError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "f" | "frames" => Ok(DeltaUnit::Frames),
            "m" | "meters" | "metres" => Ok(DeltaUnit::Meters),
            "d" | "deg" | "degrees" => Ok(DeltaUnit::Degrees),
            _ => Err(EvalError::BadOption {
                name: "delta-unit",
                value: s.to_string(),
                expected: "f (frames), m (metres) or deg (degrees)",
            }),
        }
    }
}

/// Which pose pairs the RPE uses.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RpeOptions {
    pub delta: f64,
    pub delta_unit: DeltaUnit,
    /// Overlapping pairs starting at every pose instead of consecutive, non-overlapping ones.
    pub all_pairs: bool,
}

impl Default for RpeOptions {
    fn default() -> Self {
        Self {
            delta: 1.0,
            delta_unit: DeltaUnit::Frames,
            all_pairs: false,
        }
    }
}

/// Per-pair errors: translation ‖t_E‖ (m) and rotation angle of R_E (degrees).
#[derive(Clone, Debug, PartialEq)]
pub struct RpeErrors {
    pub pairs: Vec<(usize, usize)>,
    pub translation: Vec<f64>,
    pub rotation_deg: Vec<f64>,
}

/// RPE of `est` against `gt` (associated: same length, pose k of one matches pose k of the
/// other). Pairs are chosen on the estimate, as evo does by default.
pub fn relative_pose_errors(
    gt: &[Pose],
    est: &[Pose],
    options: &RpeOptions,
) -> Result<RpeErrors, EvalError> {
    assert_eq!(gt.len(), est.len(), "RPE needs associated poses");
    let pairs = pose_pairs(est, options)?;
    let (translation, rotation_deg) = pairs
        .iter()
        .map(|&(i, j)| {
            let gt_motion = gt[i].inverse().compose(&gt[j]);
            let est_motion = est[i].inverse().compose(&est[j]);
            let error = gt_motion.inverse().compose(&est_motion);
            (
                error.translation.length(),
                rotation_angle(error.rotation).to_degrees(),
            )
        })
        .unzip();
    Ok(RpeErrors {
        pairs,
        translation,
        rotation_deg,
    })
}

/// The angle (radians, in [0, π]) of a rotation, as scipy's `Rotation.as_rotvec` norm.
pub(crate) fn rotation_angle(q: DQuat) -> f64 {
    2.0 * q.xyz().length().atan2(q.w.abs())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn units_parse_with_evo_and_long_names() {
        assert_eq!("d".parse::<DeltaUnit>().unwrap(), DeltaUnit::Degrees);
        assert_eq!("M".parse::<DeltaUnit>().unwrap(), DeltaUnit::Meters);
        let err = "s".parse::<DeltaUnit>().unwrap_err();
        assert_eq!(
            err.to_string(),
            "delta-unit = s: expected f (frames), m (metres) or deg (degrees)"
        );
    }

    #[test]
    fn rotation_angle_is_in_zero_to_pi_for_both_quaternion_signs() {
        let q = DQuat::from_rotation_y(2.5);
        assert!((rotation_angle(q) - 2.5).abs() < 1e-12);
        assert!((rotation_angle(-q) - 2.5).abs() < 1e-12);
        assert_eq!(rotation_angle(DQuat::IDENTITY), 0.0);
    }

    #[test]
    fn hand_computed_relative_error() {
        // Ground truth moves 1 m along x; the estimate moves 1 m along x and turns 10° about z
        // at the end: E = (Q_0⁻¹Q_1)⁻¹(P_0⁻¹P_1) is a pure 10° rotation.
        let gt = [Pose::IDENTITY, Pose::new(DQuat::IDENTITY, DVec3::X)];
        let turned = DQuat::from_rotation_z(10f64.to_radians());
        let est = [Pose::IDENTITY, Pose::new(turned, DVec3::X)];
        let e = relative_pose_errors(&gt, &est, &RpeOptions::default()).unwrap();
        assert_eq!(e.pairs, vec![(0, 1)]);
        assert!(e.translation[0] < 1e-15);
        assert!((e.rotation_deg[0] - 10.0).abs() < 1e-12);

        // Estimate rotated 90° about z at the start, then moving along its own x: the world
        // motion differs but the relative motion is the same, so no error.
        let r = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
        let est = [Pose::new(r, DVec3::ZERO), Pose::new(r, DVec3::Y)];
        let e = relative_pose_errors(&gt, &est, &RpeOptions::default()).unwrap();
        assert!(e.translation[0] < 1e-15 && e.rotation_deg[0] < 1e-12);

        // Estimate going 1.5 m: translation error 0.5 m.
        let est = [Pose::IDENTITY, Pose::new(DQuat::IDENTITY, DVec3::X * 1.5)];
        let e = relative_pose_errors(&gt, &est, &RpeOptions::default()).unwrap();
        assert!((e.translation[0] - 0.5).abs() < 1e-15);
    }
}
