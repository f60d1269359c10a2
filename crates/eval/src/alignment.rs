//! Aligning the estimate onto the ground truth before the errors are taken.

use std::fmt;
use std::str::FromStr;

use glam::{DMat3, DQuat, DVec3};
use rslam_core::Pose;
use serde::{Serialize, Serializer};

use crate::umeyama::umeyama;
use crate::EvalError;

/// Which transform is fitted (Umeyama, on positions only) before the errors are taken.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum AlignMode {
    /// Rotation and translation (RGB-D, stereo): evo's `-a`.
    #[default]
    Se3,
    /// Rotation, translation and scale (monocular): evo's `-as`.
    Sim3,
    /// The estimate as it is.
    None,
}

impl AlignMode {
    pub fn name(self) -> &'static str {
        match self {
            AlignMode::Se3 => "se3",
            AlignMode::Sim3 => "sim3",
            AlignMode::None => "none",
        }
    }
}

impl fmt::Display for AlignMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for AlignMode {
    type Err = EvalError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        [AlignMode::Se3, AlignMode::Sim3, AlignMode::None]
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| EvalError::BadOption {
                name: "align",
                value: s.to_string(),
                expected: "se3, sim3 or none",
            })
    }
}

/// `p ↦ scale · rotation · p + translation`, the estimate-to-ground-truth alignment.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Similarity {
    #[serde(serialize_with = "rows")]
    pub rotation: DMat3,
    pub translation: DVec3,
    pub scale: f64,
}

fn rows<S: Serializer>(m: &DMat3, serializer: S) -> Result<S::Ok, S::Error> {
    m.transpose().to_cols_array_2d().serialize(serializer)
}

impl Similarity {
    pub const IDENTITY: Similarity = Similarity {
        rotation: DMat3::IDENTITY,
        translation: DVec3::ZERO,
        scale: 1.0,
    };

    pub fn apply(&self, p: DVec3) -> DVec3 {
        self.scale * (self.rotation * p) + self.translation
    }

    /// The pose moved into the ground-truth frame: position as [`Self::apply`], orientation
    /// rotated (as evo: scale the translations, then left-multiply by `[R | t]`).
    pub fn apply_to_pose(&self, pose: &Pose) -> Pose {
        Pose::new(
            DQuat::from_mat3(&self.rotation) * pose.rotation,
            self.apply(pose.translation),
        )
    }
}

/// Fits the alignment of `est` positions onto `gt` positions (corresponding, same length).
pub fn fit_alignment(
    mode: AlignMode,
    est: &[DVec3],
    gt: &[DVec3],
) -> Result<Similarity, EvalError> {
    match mode {
        AlignMode::Se3 => umeyama(est, gt, false),
        AlignMode::Sim3 => umeyama(est, gt, true),
        AlignMode::None => Ok(Similarity::IDENTITY),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_parse_and_reject_unknown_names() {
        assert_eq!("SIM3".parse::<AlignMode>().unwrap(), AlignMode::Sim3);
        assert_eq!("none".parse::<AlignMode>().unwrap(), AlignMode::None);
        let err = "se2".parse::<AlignMode>().unwrap_err();
        assert_eq!(err.to_string(), "align = se2: expected se3, sim3 or none");
    }

    #[test]
    fn applying_to_a_pose_scales_position_and_rotates_orientation() {
        let s = Similarity {
            rotation: DMat3::from_rotation_z(std::f64::consts::FRAC_PI_2),
            translation: DVec3::new(0.0, 0.0, 1.0),
            scale: 2.0,
        };
        let pose = Pose::new(DQuat::IDENTITY, DVec3::new(1.0, 0.0, 0.0));
        let moved = s.apply_to_pose(&pose);
        assert!((moved.translation - DVec3::new(0.0, 2.0, 1.0)).length() < 1e-12);
        assert!(
            moved
                .rotation
                .angle_between(DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2))
                < 1e-9
        );
    }

    #[test]
    fn rotation_serialises_row_major() {
        let s = Similarity {
            rotation: DMat3::from_cols_array(&[1.0, 4.0, 7.0, 2.0, 5.0, 8.0, 3.0, 6.0, 9.0]),
            translation: DVec3::new(1.0, 2.0, 3.0),
            scale: 1.0,
        };
        let json = serde_json::to_string(&s).unwrap();
        assert_eq!(
            json,
            r#"{"rotation":[[1.0,2.0,3.0],[4.0,5.0,6.0],[7.0,8.0,9.0]],"translation":[1.0,2.0,3.0],"scale":1.0}"#
        );
    }
}
