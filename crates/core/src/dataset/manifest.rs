use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::{CoreError, Intrinsics};

/// Written last into every dataset: without it a dataset is incomplete.
pub const MANIFEST_FILE: &str = "rslam.json";

/// What lets someone regenerate a dataset bit for bit (formats.md, "Manifest").
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
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct ItemSeverities {
    pub item: String,
    pub per_frame: String,
}

impl Manifest {
    pub fn write(&self, dir: &Path) -> Result<(), CoreError> {
        let path = dir.join(MANIFEST_FILE);
        let text = serde_json::to_string_pretty(self)
            .map_err(|e| CoreError::bad_file(&path, e.to_string()))?;
        std::fs::write(&path, text + "\n").map_err(|e| CoreError::io(&path, e))
    }

    pub fn read(dir: &Path) -> Result<Self, CoreError> {
        let path = dir.join(MANIFEST_FILE);
        let text = std::fs::read_to_string(&path).map_err(|e| CoreError::io(&path, e))?;
        serde_json::from_str(&text)
            .map_err(|e| CoreError::bad_file(&path, format!("not an rslam manifest: {e}")))
    }
}
