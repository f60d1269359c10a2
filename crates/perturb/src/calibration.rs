//! Calibration perturbations of a multi-sensor rig: `baseline:σ`, `extrinsic_rot:DEG` and
//! `extrinsic_trans:M`, each in one of three modes.
//!
//! - rendered (the default): the sensor really sits elsewhere (the mount moved). Images and IMU
//!   readings are made with the perturbed placement; the calibration files state the nominal one.
//! - `@dynamic`: rendered, with a new draw on every frame of the moved camera (the mount shakes).
//!   Not for the IMU: its readings come from the body's smooth motion, and a mount that jumps on
//!   every sample has no angular velocity or acceleration to read. Not with `@calibration`: a
//!   calibration file holds one value per sequence.
//! - `@calibration`: the sensor is where it should be, images are nominal, and the written
//!   calibration is perturbed (what the seed paper did to the real EuRoC sequences).
//!
//! Draws (docs/src/perturbations.md §2): a sensor's draws are keyed by (that sensor's seed, item name,
//! frame, purpose); a per-sequence draw is frame 0's, so frame k's draw does not depend on how
//! many frames there are. What each item moves:
//! - `baseline:σ` moves cam1 by δ ~ N(0, σ) metres along cam0's x axis (the baseline axis of a
//!   rectified pair).
//! - `extrinsic_rot:DEG` turns the sensor about its own centre, `T_BS' = T_BS · Rx(αx)·Ry(αy)·Rz(αz)`
//!   with α ~ N(0, DEG°) per axis of the sensor's frame.
//! - `extrinsic_trans:M` shifts the sensor by Δt ~ N(0, M) per axis of its own frame.
//!
//! `SENSOR:extrinsic_*` moves that sensor (`cam1`, `imu0`); without a sensor each camera draws its
//! own offset (the IMU, the body frame's reference, only when named).

use std::fmt;

use glam::{DQuat, DVec3};
use rslam_core::Pose;
use serde::{Deserialize, Serialize};

use crate::applies::{ItemEntry, Need};
use crate::rng::RngKey;

pub const BASELINE: &str = "baseline";
pub const EXTRINSIC_ROT: &str = "extrinsic_rot";
pub const EXTRINSIC_TRANS: &str = "extrinsic_trans";

/// The modes every calibration item takes, for `rslam list`.
macro_rules! modes {
    () => {
        "rendered (default): images and IMU made with the moved sensor, the calibration files state the nominal one; @dynamic: rendered, a new draw on every frame of the moved camera (per-frame draws in calibration_per_frame.csv; not with @calibration); @calibration: images nominal, the written calibration moved; the manifest records both; a rendered item needs a scene, @calibration also takes a recorded EuRoC dataset"
    };
}

/// The calibration items; the needs are the rendered mode's (`@calibration` needs a rig only).
pub static CALIBRATION_ITEMS: &[ItemEntry] = &[
    ItemEntry {
        name: BASELINE,
        syntax: "baseline:METRES[@dynamic|@calibration]",
        description: concat!("cam1 moved by δ ~ N(0, σ) along cam0's x axis, once per sequence; ", modes!()),
        needs: &[Need::Rig, Need::Scene],
    },
    ItemEntry {
        name: EXTRINSIC_ROT,
        syntax: "[SENSOR:]extrinsic_rot:DEGREES[@dynamic|@calibration]",
        description: concat!("T_BS' = T_BS·Rx·Ry·Rz, per-axis angles ~ N(0, D°) in the sensor's frame, one draw per sequence; SENSOR cam0, cam1, imu0, …, without one every camera draws its own; @dynamic for cameras only (imu0 per sequence); ", modes!()),
        needs: &[Need::Rig, Need::Scene],
    },
    ItemEntry {
        name: EXTRINSIC_TRANS,
        syntax: "[SENSOR:]extrinsic_trans:METRES[@dynamic|@calibration]",
        description: concat!("T_BS' = T_BS·(I, Δt), Δt ~ N(0, M) per axis of the sensor's frame, one draw per sequence; SENSOR and @dynamic as for extrinsic_rot; ", modes!()),
        needs: &[Need::Rig, Need::Scene],
    },
];

const PURPOSE_OFFSET: u32 = 1;

/// Where a calibration perturbation shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CalibrationMode {
    /// Images and IMU made with the perturbed rig; the files state the nominal one.
    Rendered,
    /// Images and IMU nominal; the files state the perturbed rig.
    Calibration,
}

/// One calibration item of a spec.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CalibrationItem {
    /// One of [`NAMES`].
    pub name: String,
    /// The sensor it moves (`cam1`, `imu0`); `None`: every camera (`baseline`: cam1).
    pub sensor: Option<String>,
    /// Standard deviation: metres (`baseline`, `extrinsic_trans`) or degrees (`extrinsic_rot`).
    pub sigma: f64,
    pub mode: CalibrationMode,
    /// A new draw on every frame of the moved camera (`@dynamic`, rendered).
    pub dynamic: bool,
}

impl CalibrationItem {
    /// `name:value[@mode]` addressed to `sensor`; the error is the message for the item.
    pub fn parse(
        sensor: Option<&str>,
        name: &str,
        value: &str,
        mode: Option<&str>,
    ) -> Result<Self, String> {
        let unit = if name == EXTRINSIC_ROT {
            "degrees"
        } else {
            "metres"
        };
        let sigma = value
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && *v >= 0.0)
            .ok_or_else(|| {
                format!("expected a standard deviation in {unit} ≥ 0, e.g. {name}:0.01")
            })?;
        if name == BASELINE && sensor.is_some() {
            return Err("baseline moves cam1 along cam0's x axis and takes no sensor".into());
        }
        let modes: Vec<&str> =
            mode.map_or_else(Vec::new, |m| m.split('@').map(str::trim).collect());
        let (mode, dynamic) = match modes.as_slice() {
            [] => (CalibrationMode::Rendered, false),
            ["calibration"] => (CalibrationMode::Calibration, false),
            ["dynamic"] => (CalibrationMode::Rendered, true),
            [a, b] if [*a, *b].contains(&"dynamic") && [*a, *b].contains(&"calibration") => {
                return Err("@dynamic and @calibration exclude each other: a calibration file holds one value per sequence".into());
            }
            _ => {
                let m = modes.join("@");
                return Err(format!(
                    "unknown mode '@{m}'; valid: @calibration, @dynamic (rendered is the default)"
                ));
            }
        };
        if let Some(imu) = sensor.filter(|s| dynamic && s.starts_with("imu")) {
            return Err(format!("@dynamic moves a camera on every frame; {imu} is the body frame its readings are made in, and a mount that jumps on every sample has no angular velocity or acceleration to read: use {imu}:{name}:{value} (once per sequence)"));
        }
        Ok(Self {
            name: name.to_string(),
            sensor: sensor.map(str::to_string),
            sigma,
            mode,
            dynamic,
        })
    }

    /// Whether this item moves `sensor` (`cam0`, `imu0`, …; `cam1` for `baseline`).
    pub fn moves(&self, sensor: &str) -> bool {
        match (&self.sensor, self.name.as_str()) {
            (_, BASELINE) => sensor == "cam1",
            (Some(s), _) => s == sensor,
            (None, _) => sensor.starts_with("cam"),
        }
    }

    /// Three draws ~ N(0, σ) for frame `frame` (0 for a per-sequence draw) with the moved
    /// sensor's `seed`.
    fn draw3(&self, seed: u64, frame: u32) -> DVec3 {
        let key = RngKey::new(seed, &self.name, frame, PURPOSE_OFFSET);
        DVec3::from_array(std::array::from_fn(|axis| {
            self.sigma * key.normal_f64([axis as u32, 0, 0, 0])
        }))
    }

    /// `baseline`'s δ in metres on frame `frame` (frame 0 for a per-sequence draw), drawn with
    /// cam1's seed.
    pub fn baseline_offset(&self, cam1_seed: u64, frame: u32) -> f64 {
        self.draw3(cam1_seed, frame).x
    }

    /// The sensor's move `Δ` under an `extrinsic_*` item on frame `frame` (0 for a per-sequence
    /// draw) with the sensor's `seed`: `T_BS' = T_BS · Δ`.
    pub fn extrinsic_offset(&self, seed: u64, frame: u32) -> Pose {
        let d = self.draw3(seed, frame);
        if self.name == EXTRINSIC_ROT {
            let a = d * std::f64::consts::PI / 180.0;
            let rotation = DQuat::from_rotation_x(a.x)
                * DQuat::from_rotation_y(a.y)
                * DQuat::from_rotation_z(a.z);
            Pose::new(rotation, DVec3::ZERO)
        } else {
            Pose::new(DQuat::IDENTITY, d)
        }
    }

    /// `T_BS` of the sensor after an `extrinsic_*` item's per-sequence draw with the sensor's
    /// `seed`.
    pub fn apply_extrinsic(&self, body_from_sensor: &Pose, seed: u64) -> Pose {
        body_from_sensor.compose(&self.extrinsic_offset(seed, 0))
    }
}

/// cam1's `T_BS` moved by `delta` metres along cam0's x axis.
pub fn move_along_baseline(body_from_cam0: &Pose, body_from_cam1: &Pose, delta: f64) -> Pose {
    Pose::new(
        body_from_cam1.rotation,
        body_from_cam1.translation + body_from_cam0.rotation * DVec3::X * delta,
    )
}

impl fmt::Display for CalibrationItem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(sensor) = &self.sensor {
            write!(f, "{sensor}:")?;
        }
        write!(f, "{}:{}", self.name, self.sigma)?;
        match (self.mode, self.dynamic) {
            (CalibrationMode::Calibration, _) => write!(f, "@calibration"),
            (CalibrationMode::Rendered, true) => write!(f, "@dynamic"),
            (CalibrationMode::Rendered, false) => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn item(text: &str) -> CalibrationItem {
        let spec = crate::PerturbSpec::parse(text).unwrap();
        assert_eq!(spec.calibration.len(), 1, "{text}");
        spec.calibration[0].clone()
    }

    #[test]
    fn per_sequence_draws_are_normal_with_the_stated_sigma_across_seeds() {
        let baseline = item("baseline:0.01");
        let draws: Vec<f64> = (0..4000u64)
            .map(|seed| baseline.baseline_offset(seed, 0))
            .collect();
        let n = draws.len() as f64;
        let mean = draws.iter().sum::<f64>() / n;
        let std = (draws.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        assert!(mean.abs() < 4.0 * 0.01 / n.sqrt(), "mean {mean}");
        assert!((std / 0.01 - 1.0).abs() < 0.05, "std {std}");
    }

    #[test]
    fn extrinsic_rot_turns_about_the_sensor_centre_and_trans_shifts_in_its_frame() {
        let t_bs = Pose::new(DQuat::from_rotation_z(0.7), DVec3::new(0.1, -0.2, 0.3));
        let rot = item("cam1:extrinsic_rot:2").apply_extrinsic(&t_bs, 5);
        assert_eq!(rot.translation, t_bs.translation);
        let angle = rot.rotation.angle_between(t_bs.rotation).to_degrees();
        assert!(angle > 0.0 && angle < 4.0 * 2.0 * 3f64.sqrt(), "{angle}");
        let trans = item("imu0:extrinsic_trans:0.01").apply_extrinsic(&t_bs, 5);
        assert!(trans.rotation.angle_between(t_bs.rotation) < 1e-12);
        let shift = trans.translation - t_bs.translation;
        assert!(shift.length() > 0.0 && shift.length() < 0.06, "{shift}");
        // The same item, seed and sensor pose give the same draw; another seed another.
        assert_eq!(item("cam1:extrinsic_rot:2").apply_extrinsic(&t_bs, 5), rot);
        assert_ne!(item("cam1:extrinsic_rot:2").apply_extrinsic(&t_bs, 6), rot);
    }

    /// Mean and sample standard deviation.
    fn mean_std(values: &[f64]) -> (f64, f64) {
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, var.sqrt())
    }

    #[test]
    fn dynamic_extrinsic_draws_are_per_frame_normal_per_axis_and_repeatable() {
        let n = 4000u32;
        for (text, sigma) in [
            ("cam1:extrinsic_rot:0.5@dynamic", 0.5),
            ("extrinsic_trans:0.01@dynamic", 0.01),
        ] {
            let item = item(text);
            assert!(item.dynamic && item.mode == CalibrationMode::Rendered);
            // Per axis: the Rx·Ry·Rz angles in degrees, or the shift in metres.
            let axes = |frame: u32| -> [f64; 3] {
                let delta = item.extrinsic_offset(9, frame);
                if item.name == EXTRINSIC_ROT {
                    let (x, y, z) = delta.rotation.to_euler(glam::EulerRot::XYZ);
                    let again = DQuat::from_rotation_x(x)
                        * DQuat::from_rotation_y(y)
                        * DQuat::from_rotation_z(z);
                    assert!(
                        again.abs_diff_eq(delta.rotation, 1e-12),
                        "{again} {delta:?}"
                    );
                    assert_eq!(delta.translation, DVec3::ZERO);
                    [x.to_degrees(), y.to_degrees(), z.to_degrees()]
                } else {
                    assert_eq!(delta.rotation, DQuat::IDENTITY);
                    delta.translation.to_array()
                }
            };
            let draws: Vec<[f64; 3]> = (0..n).map(axes).collect();
            for axis in 0..3 {
                let values: Vec<f64> = draws.iter().map(|d| d[axis]).collect();
                let (mean, std) = mean_std(&values);
                assert!(
                    mean.abs() < 4.0 * sigma / f64::from(n).sqrt(),
                    "{text} axis {axis}: mean {mean}"
                );
                // The sample std's standard error is σ/√(2n) ≈ 1.1 % of σ here.
                assert!(
                    (std / sigma - 1.0).abs() < 0.05,
                    "{text} axis {axis}: std {std}"
                );
                let lag1 = values
                    .windows(2)
                    .map(|w| (w[0] - mean) * (w[1] - mean))
                    .sum::<f64>()
                    / (f64::from(n - 1) * std * std);
                assert!(lag1.abs() < 0.05, "{text} axis {axis}: lag-1 {lag1}");
            }
            // The axes are independent draws.
            let (x, y): (Vec<f64>, Vec<f64>) = draws.iter().map(|d| (d[0], d[1])).unzip();
            let ((mx, sx), (my, sy)) = (mean_std(&x), mean_std(&y));
            let xy = x
                .iter()
                .zip(&y)
                .map(|(a, b)| (a - mx) * (b - my))
                .sum::<f64>()
                / (f64::from(n - 1) * sx * sy);
            assert!(xy.abs() < 0.05, "{text}: x–y correlation {xy}");
            // Keyed by seed and frame only: the same again, another seed or frame another.
            assert_eq!(item.extrinsic_offset(9, 17), item.extrinsic_offset(9, 17));
            assert_ne!(item.extrinsic_offset(9, 17), item.extrinsic_offset(10, 17));
            assert_ne!(item.extrinsic_offset(9, 17), item.extrinsic_offset(9, 18));
            // Frame 0 is the per-sequence draw.
            let t_bs = Pose::new(DQuat::from_rotation_z(0.3), DVec3::new(0.1, 0.0, 0.0));
            assert_eq!(
                item.apply_extrinsic(&t_bs, 9),
                t_bs.compose(&item.extrinsic_offset(9, 0))
            );
        }
    }

    #[test]
    fn the_baseline_moves_cam1_along_cam0_x() {
        let cam0 = Pose::new(DQuat::from_rotation_y(0.5), DVec3::new(1.0, 2.0, 3.0));
        let cam1 = cam0.compose(&Pose::new(DQuat::IDENTITY, DVec3::X * 0.11));
        let moved = move_along_baseline(&cam0, &cam1, 0.02);
        let cam0_from_cam1 = cam0.inverse().compose(&moved);
        assert!((cam0_from_cam1.translation - DVec3::X * 0.13).length() < 1e-12);
    }

    #[test]
    fn which_sensors_an_item_moves() {
        assert!(item("baseline:0.01").moves("cam1"));
        assert!(!item("baseline:0.01").moves("cam0"));
        let every_camera = item("extrinsic_rot:1");
        assert!(every_camera.moves("cam0") && every_camera.moves("cam1"));
        assert!(!every_camera.moves("imu0"));
        assert!(item("imu0:extrinsic_trans:0.01").moves("imu0"));
        assert!(!item("cam1:extrinsic_trans:0.01").moves("cam0"));
    }
}
