//! The suite file `suite.toml`: one `[[sequence]]` per dataset, with `[defaults]` for what most
//! rows share. Read with line numbers in every error; written by `rslam suite init`.
//!
//! ```toml
//! seed = 0                      # every row without its own seed gets mix(seed, name)
//! [defaults]
//! frames = 2000                 # also: format, camera, rig, rate, scene, traj, depth_png,
//!                               #   bag_depth, bag_tf, bag_compression
//! [[sequence]]
//! name = "room0__fog-3"         # <scene>__<setting>, the folder under datasets/
//! scene = "room0"               # built-in scene or mesh file (relative to this file)
//! perturb = "fog:3"             # a --perturb spec; empty or absent: clean
//! ```

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::SuiteError;

pub const SUITE_FILE: &str = "suite.toml";

/// The file as written: every field of a row optional, so that `[defaults]` can fill it.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SuiteFile {
    #[serde(default)]
    pub seed: u64,
    #[serde(default, skip_serializing_if = "SequenceFields::is_empty")]
    pub defaults: SequenceFields,
    #[serde(default, rename = "sequence")]
    pub sequences: Vec<toml::Spanned<SequenceFields>>,
}

/// One `[[sequence]]` row, or `[defaults]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SequenceFields {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scene: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub perturb: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub frames: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub format: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub camera: Option<String>,
    /// A rig preset: `stereo`, `stereo-imu` instead of one camera, with `format = "euroc"`;
    /// `rgbd-imu`, the camera and an IMU, with `format = "tum"`; `rgbd`, the camera alone.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rig: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rate: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub traj: Option<PathBuf>,
    /// `fast` or `small` (see `rslam render --depth-png`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub depth_png: Option<String>,
    /// A bag's options (`format = "ros2"`; see `rslam render --bag-depth`, `--bag-tf`,
    /// `--bag-compression`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bag_depth: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bag_tf: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bag_compression: Option<String>,
}

impl SequenceFields {
    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }

    /// This row's fields, each taken from `defaults` where the row leaves it out.
    pub fn or(&self, defaults: &SequenceFields) -> SequenceFields {
        SequenceFields {
            name: self.name.clone().or_else(|| defaults.name.clone()),
            scene: self.scene.clone().or_else(|| defaults.scene.clone()),
            perturb: self.perturb.clone().or_else(|| defaults.perturb.clone()),
            seed: self.seed.or(defaults.seed),
            frames: self.frames.or(defaults.frames),
            format: self.format.clone().or_else(|| defaults.format.clone()),
            camera: self.camera.clone().or_else(|| defaults.camera.clone()),
            rig: self.rig.clone().or_else(|| defaults.rig.clone()),
            rate: self.rate.or(defaults.rate),
            traj: self.traj.clone().or_else(|| defaults.traj.clone()),
            depth_png: self
                .depth_png
                .clone()
                .or_else(|| defaults.depth_png.clone()),
            bag_depth: self
                .bag_depth
                .clone()
                .or_else(|| defaults.bag_depth.clone()),
            bag_tf: self.bag_tf.or(defaults.bag_tf),
            bag_compression: self
                .bag_compression
                .clone()
                .or_else(|| defaults.bag_compression.clone()),
        }
    }
}

impl SuiteFile {
    /// Parses `text`, the contents of `path` (named in errors).
    pub fn parse(path: &Path, text: &str) -> Result<Self, SuiteError> {
        toml::from_str(text).map_err(|e| SuiteError::SuiteFile {
            path: path.to_path_buf(),
            line: e.span().map_or(0, |span| line_of(text, span.start)),
            message: e.message().trim_end().replace('\n', "; "),
        })
    }

    /// The TOML text, after a comment that says what the file is.
    pub fn to_text(&self, header: &str) -> Result<String, SuiteError> {
        let body = toml::to_string(self).map_err(|e| SuiteError::SuiteFile {
            path: PathBuf::from(SUITE_FILE),
            line: 0,
            message: e.to_string(),
        })?;
        let comment: String = header.lines().map(|l| format!("# {l}\n")).collect();
        Ok(format!("{comment}\n{body}"))
    }
}

pub(crate) fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}
