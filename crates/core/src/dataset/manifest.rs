use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::dataset::ros2::BagOptions;
use crate::dataset::{write_atomically, DepthPng};
use crate::{read_text_file, CoreError, Distortion, Intrinsics};

/// Written last into every dataset: without it a dataset is incomplete.
pub const MANIFEST_FILE: &str = "rslam.json";

/// What lets someone regenerate a dataset bit for bit (docs/src/formats.md, "Manifest").
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Manifest {
    pub tool: String,
    pub tool_version: String,
    /// The command that made it, as typed.
    pub command: Vec<String>,
    /// Built-in scene name, mesh path or source dataset path.
    pub source: String,
    /// Content hash of the scene (or empty for an existing dataset).
    pub source_hash: String,
    /// Dataset layout; `None` for a folder of perturbed images.
    pub format: Option<crate::dataset::DatasetFormat>,
    /// `None` for a folder of perturbed images.
    pub camera: Option<Intrinsics>,
    /// The lens the frames were seen through; absent (not written) without one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distortion: Option<Distortion>,
    /// How the depth PNGs are compressed (the samples are the same either way). Manifests from
    /// before this field read as `fast`, which is what they wrote; folders of images hold none.
    #[serde(default)]
    pub depth_png: DepthPng,
    /// How a ROS 2 bag's depth, `/tf` and chunks are written; absent when as by default.
    #[serde(default, skip_serializing_if = "BagOptions::is_default")]
    pub bag: BagOptions,
    pub rate_hz: f64,
    pub frame_count: usize,
    pub seed: u64,
    /// The parsed perturbation spec in canonical form, and as structured data.
    pub perturbation: String,
    pub perturbation_parsed: serde_json::Value,
    /// Per sensor perturbation item: one digit per output frame, the severity it received (0 = clean).
    pub severities: Vec<ItemSeverities>,
    /// Per output frame: the source frame its RGB and its depth come from.
    pub rgb_source: Vec<usize>,
    pub depth_source: Vec<usize>,
    /// Anything else a stage wants recorded (e.g. drawn trajectory deviations).
    pub extra: serde_json::Value,
    /// BLAKE3 (hex) of `rslam.b3sum`, the checksum list of every file: one digest for the whole
    /// content. Empty until the run has finished.
    #[serde(default)]
    pub content_digest: String,
}

/// The severity one frame corruption gave each output frame: one digit per frame when all are
/// whole (`"0352"`), the numbers separated by spaces when any is real (`"0 2.5 1.25"`).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct ItemSeverities {
    pub item: String,
    pub per_frame: String,
}

impl ItemSeverities {
    /// `per_frame` in its short form when every severity is whole.
    pub fn new(item: String, severities: &[f64]) -> Self {
        let whole = severities
            .iter()
            .all(|s| s.fract() == 0.0 && (0.0..=9.0).contains(s));
        let per_frame = if whole {
            severities
                .iter()
                .map(|&s| char::from(b'0' + s as u8))
                .collect()
        } else {
            let texts: Vec<String> = severities.iter().map(|s| s.to_string()).collect();
            texts.join(" ")
        };
        Self { item, per_frame }
    }

    /// The severities `per_frame` holds, in either form; `None` where it is neither.
    pub fn values(&self) -> Option<Vec<f64>> {
        if self.per_frame.contains(' ') || self.per_frame.contains('.') {
            self.per_frame
                .split(' ')
                .map(|s| s.parse::<f64>().ok())
                .collect()
        } else {
            self.per_frame
                .bytes()
                .map(|b| b.is_ascii_digit().then(|| (b - b'0') as f64))
                .collect()
        }
    }
}

impl Manifest {
    /// Writes `dir/rslam.json` through a temporary name and a rename: it appears whole or not.
    pub fn write(&self, dir: &Path) -> Result<(), CoreError> {
        self.write_as(dir, MANIFEST_FILE)
    }

    /// Writes this manifest as `dir/name` (also the run record of a run in progress), atomically.
    pub fn write_as(&self, dir: &Path, name: &str) -> Result<(), CoreError> {
        let path = dir.join(name);
        let value =
            serde_json::to_value(self).map_err(|e| CoreError::bad_file(&path, e.to_string()))?;
        let mut text = String::new();
        write_compact_pretty(&value, 0, &mut text);
        write_atomically(&path, (text + "\n").as_bytes())
    }

    pub fn read(dir: &Path) -> Result<Self, CoreError> {
        Self::read_as(dir, MANIFEST_FILE)
    }

    pub fn read_as(dir: &Path, name: &str) -> Result<Self, CoreError> {
        let path = dir.join(name);
        let text = read_text_file(&path, "an rslam manifest (JSON)")?;
        let manifest: Manifest = serde_json::from_str(&text)
            .map_err(|e| CoreError::bad_file(&path, format!("not an rslam manifest: {e}")))?;
        if !(manifest.rate_hz.is_finite() && manifest.rate_hz > 0.0) {
            return Err(CoreError::bad_file(
                &path,
                format!(
                    "rate_hz {}: expected a positive frame rate in Hz",
                    manifest.rate_hz
                ),
            ));
        }
        if let Some(camera) = &manifest.camera {
            camera
                .check()
                .map_err(|message| CoreError::bad_file(&path, format!("camera.{message}")))?;
        }
        Ok(manifest)
    }

    /// What the run does, without how it was typed or what it made: two runs with the same job
    /// write the same bytes, so one may finish what the other started.
    pub fn job(&self) -> Manifest {
        Manifest {
            command: Vec::new(),
            content_digest: String::new(),
            ..self.clone()
        }
    }
}

/// Pretty JSON with arrays of scalars on one line, so per-frame lists stay one line each.
fn write_compact_pretty(value: &serde_json::Value, indent: usize, out: &mut String) {
    use serde_json::Value;
    let pad = |n: usize| "  ".repeat(n);
    match value {
        Value::Object(map) if !map.is_empty() => {
            out.push_str("{\n");
            for (i, (key, v)) in map.iter().enumerate() {
                out.push_str(&format!(
                    "{}{}: ",
                    pad(indent + 1),
                    Value::String(key.clone())
                ));
                write_compact_pretty(v, indent + 1, out);
                out.push_str(if i + 1 < map.len() { ",\n" } else { "\n" });
            }
            out.push_str(&format!("{}}}", pad(indent)));
        }
        Value::Array(items) if items.iter().any(|v| v.is_object() || v.is_array()) => {
            out.push_str("[\n");
            for (i, v) in items.iter().enumerate() {
                out.push_str(&pad(indent + 1));
                write_compact_pretty(v, indent + 1, out);
                out.push_str(if i + 1 < items.len() { ",\n" } else { "\n" });
            }
            out.push_str(&format!("{}]", pad(indent)));
        }
        other => out.push_str(&other.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn item_severities_keep_digits_for_whole_ones_and_read_back_both_forms() {
        let whole = ItemSeverities::new("fog:3@dynamic".into(), &[0.0, 3.0, 2.0]);
        assert_eq!(whole.per_frame, "032");
        assert_eq!(whole.values(), Some(vec![0.0, 3.0, 2.0]));
        let real = ItemSeverities::new("fog:2.5@dynamic".into(), &[0.0, 2.5, 1.25]);
        assert_eq!(real.per_frame, "0 2.5 1.25");
        assert_eq!(real.values(), Some(vec![0.0, 2.5, 1.25]));
        let single = ItemSeverities::new("fog:2.5".into(), &[2.5]);
        assert_eq!(single.values(), Some(vec![2.5]));
    }

    #[test]
    fn depth_png_is_part_of_the_job_and_older_manifests_read_as_fast() {
        let mut value = serde_json::json!({
            "tool": "rslam", "tool_version": "0.1.0", "command": [], "source": "room0",
            "source_hash": "", "format": "replica", "camera": null, "rate_hz": 20.0,
            "frame_count": 0, "seed": 0, "perturbation": "", "perturbation_parsed": null,
            "severities": [], "rgb_source": [], "depth_source": [], "extra": null
        });
        let older: Manifest = serde_json::from_value(value.clone()).unwrap();
        assert_eq!(older.depth_png, DepthPng::Fast);
        value["depth_png"] = "small".into();
        let small: Manifest = serde_json::from_value(value).unwrap();
        assert_eq!(small.depth_png, DepthPng::Small);
        assert_ne!(small.job(), older.job());
        assert_eq!(serde_json::to_value(&small).unwrap()["depth_png"], "small");
    }

    #[test]
    fn bag_options_are_part_of_the_job_and_absent_when_default() {
        let value = serde_json::json!({
            "tool": "rslam", "tool_version": "0.1.0", "command": [], "source": "room0",
            "source_hash": "", "format": "ros2", "camera": null, "rate_hz": 20.0,
            "frame_count": 0, "seed": 0, "perturbation": "", "perturbation_parsed": null,
            "severities": [], "rgb_source": [], "depth_source": [], "extra": null
        });
        let plain: Manifest = serde_json::from_value(value).unwrap();
        assert!(serde_json::to_value(&plain).unwrap().get("bag").is_none());
        let metres = Manifest {
            bag: BagOptions {
                depth: crate::dataset::ros2::BagDepth::Metres,
                ..BagOptions::default()
            },
            ..plain.clone()
        };
        assert_ne!(metres.job(), plain.job());
        let written = serde_json::to_value(&metres).unwrap();
        assert_eq!(written["bag"], serde_json::json!({"depth": "32FC1"}));
        assert_eq!(serde_json::from_value::<Manifest>(written).unwrap(), metres);
    }

    /// serde_json's default float parser read 98752.20364687759 back as 98752.2036468776, so the
    /// same job looked like another one; found by the manifest round-trip property.
    #[test]
    fn camera_numbers_read_back_bit_for_bit() {
        let mut manifest: Manifest = serde_json::from_value(serde_json::json!({
            "tool": "rslam", "tool_version": "0.1.0", "command": [], "source": "room0",
            "source_hash": "", "format": "tum", "camera": null, "rate_hz": 0.001,
            "frame_count": 0, "seed": 0, "perturbation": "", "perturbation_parsed": null,
            "severities": [], "rgb_source": [], "depth_source": [], "extra": null
        }))
        .unwrap();
        manifest.camera = Some(Intrinsics {
            fx: 98752.20364687759,
            fy: 98752.20364687759,
            ..Intrinsics::TUM
        });
        let dir = tempfile::tempdir().unwrap();
        manifest.write(dir.path()).unwrap();
        assert_eq!(Manifest::read(dir.path()).unwrap(), manifest);
    }

    /// Found by the fuzzer: a negative rate passed the manifest and failed later without a file.
    #[test]
    fn a_rate_that_is_not_positive_is_refused_naming_the_manifest() {
        let dir = tempfile::tempdir().unwrap();
        for rate in ["-1", "0"] {
            let text = format!(
                r#"{{"tool": "rslam", "tool_version": "0.1.0", "command": [], "source": "room0",
                "source_hash": "", "format": "replica", "camera": null, "rate_hz": {rate},
                "frame_count": 0, "seed": 0, "perturbation": "", "perturbation_parsed": null,
                "severities": [], "rgb_source": [], "depth_source": [], "extra": null}}"#
            );
            std::fs::write(dir.path().join(MANIFEST_FILE), text).unwrap();
            let message = Manifest::read(dir.path()).unwrap_err().to_string();
            assert!(message.contains(MANIFEST_FILE), "{message}");
            assert!(message.contains("positive frame rate"), "{message}");
        }
    }

    #[test]
    fn scalar_arrays_stay_on_one_line_and_the_text_parses_back() {
        let value = serde_json::json!({"a": [1, 2, 3], "b": {"c": "x", "d": [{"e": []}]}});
        let mut text = String::new();
        write_compact_pretty(&value, 0, &mut text);
        assert!(text.contains("\"a\": [1,2,3]"), "{text}");
        assert_eq!(
            serde_json::from_str::<serde_json::Value>(&text).unwrap(),
            value
        );
    }
}
