//! What `rslam list` shows: every catalogue entry and every trajectory and stream item, with
//! its parameters at each severity and one line on what it does.

use serde::Serialize;

use crate::calibration::{BASELINE, EXTRINSIC_ROT, EXTRINSIC_TRANS};
use crate::imu::IMU_ITEMS;
use crate::sensor::{SensorEntry, SENSOR_ITEMS};
use crate::trajectory::{SMOOTH_BAND_HZ, SMOOTH_TONES};
use crate::{Group, CATALOGUE};

/// One row of `rslam list`.
#[derive(Clone, Debug, Serialize)]
pub struct ListEntry {
    pub name: &'static str,
    /// "image", "depth", "trajectory", "stream", "sensor", "calibration" or "imu".
    pub group: &'static str,
    /// How to write it in a spec.
    pub syntax: String,
    pub description: String,
    /// Parameters at severities 1..=5; empty for trajectory and stream items.
    pub parameters: Vec<String>,
}

/// Every perturbation: image, then depth corruptions (catalogue order), then trajectory and
/// stream items, then sensor effects, then a rig's calibration items, then IMU items.
pub fn listing() -> Vec<ListEntry> {
    let mut entries: Vec<ListEntry> = CATALOGUE
        .iter()
        .map(|e| {
            let mut syntax = format!("{}:1-5[@dynamic]", e.name);
            if let Some(form) = &e.explicit {
                syntax.push_str(&format!(" | {}", form.syntax));
            }
            ListEntry {
                name: e.name,
                group: match e.group {
                    Group::Image => "image",
                    Group::Depth => "depth",
                },
                syntax,
                description: e.description.to_string(),
                parameters: e.parameter_table().to_vec(),
            }
        })
        .collect();
    entries.sort_by_key(|e| e.group != "image");
    let smooth = format!(
        "@smooth: temporally correlated instead, per axis a sum of {SMOOTH_TONES} sinusoids with \
         frequencies uniform in {}-{} Hz and random phases, same marginal σ",
        SMOOTH_BAND_HZ.0, SMOOTH_BAND_HZ.1
    );
    let sequence = [
        (
            "rot",
            "trajectory",
            "rot:DEGREES[@smooth]",
            format!("R' = R·Rx·Ry·Rz, per-axis angles ~ N(0, D°), each pose independently (benchmark: 1, 3, 5); {smooth}"),
        ),
        (
            "trans",
            "trajectory",
            "trans:METRES[@smooth]",
            format!("t' = t + Δt, Δt ~ N(0, M) per world axis, each pose independently (benchmark: 0.0125, 0.025, 0.05); {smooth}"),
        ),
        (
            "fast",
            "stream",
            "fast:K",
            "keeps frames 0, K, 2K, … re-stamped at the sensor rate: the camera moves K× faster (benchmark: 2, 4, 8)".to_string(),
        ),
        (
            "misalign",
            "stream",
            "misalign:FRAMES[@dynamic]",
            "depth lags colour: RGB frame i pairs with depth frame max(0, i−D); @dynamic: D_i uniform in {D−1, D, D+1} per frame (benchmark: 5, 10, 20)".to_string(),
        ),
    ];
    entries.extend(
        sequence
            .into_iter()
            .map(|(name, group, syntax, description)| ListEntry {
                name,
                group,
                syntax: syntax.to_string(),
                description,
                parameters: Vec::new(),
            }),
    );
    entries.extend(item_entries("sensor", SENSOR_ITEMS));
    let modes = "rendered (default): images and IMU made with the moved sensor, the calibration files state the nominal one; @dynamic: rendered, a new draw on every frame of the moved camera (per-frame draws in calibration_per_frame.csv; not with @calibration); @calibration: images nominal, the written calibration moved; the manifest records both; needs a rig (--rig, or a EuRoC input: @calibration only)";
    let calibration = [
        (
            BASELINE,
            "baseline:METRES[@dynamic|@calibration]",
            format!("cam1 moved by δ ~ N(0, σ) along cam0's x axis, once per sequence; {modes}"),
        ),
        (
            EXTRINSIC_ROT,
            "[SENSOR:]extrinsic_rot:DEGREES[@dynamic|@calibration]",
            format!("T_BS' = T_BS·Rx·Ry·Rz, per-axis angles ~ N(0, D°) in the sensor's frame, one draw per sequence; SENSOR cam0, cam1, imu0, …, without one every camera draws its own; @dynamic for cameras only (imu0 per sequence); {modes}"),
        ),
        (
            EXTRINSIC_TRANS,
            "[SENSOR:]extrinsic_trans:METRES[@dynamic|@calibration]",
            format!("T_BS' = T_BS·(I, Δt), Δt ~ N(0, M) per axis of the sensor's frame, one draw per sequence; SENSOR and @dynamic as for extrinsic_rot; {modes}"),
        ),
    ];
    entries.extend(
        calibration
            .into_iter()
            .map(|(name, syntax, description)| ListEntry {
                name,
                group: "calibration",
                syntax: syntax.to_string(),
                description,
                parameters: Vec::new(),
            }),
    );
    entries.extend(item_entries("imu", IMU_ITEMS));
    entries
}

/// Listing entries of items described by their syntax alone (sensor effects, IMU items).
fn item_entries(group: &'static str, items: &'static [SensorEntry]) -> Vec<ListEntry> {
    items
        .iter()
        .map(|e| ListEntry {
            name: e.name,
            group,
            syntax: e.syntax.to_string(),
            description: e.description.to_string(),
            parameters: Vec::new(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_every_spec_name_once() {
        let names: Vec<&str> = listing().iter().map(|e| e.name).collect();
        assert_eq!(names.len(), crate::all_names().len());
        for name in crate::all_names() {
            assert_eq!(names.iter().filter(|&&n| n == name).count(), 1, "{name}");
        }
        assert!(listing()
            .iter()
            .filter(|e| e.group == "image" || e.group == "depth")
            .all(|e| e.parameters.len() == 5));
    }
}
