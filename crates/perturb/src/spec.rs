//! The `--perturb` grammar of perturbations.md §1:
//!
//! ```text
//! spec  := item (',' item)*
//! item  := NAME ':' SEVERITY ['@static' | '@dynamic']      image and depth corruptions
//!        | NAME ':' EXPLICIT                               e.g. depth_range:0.42-10
//!        | 'rot:' DEGREES ['@smooth'] | 'trans:' METRES ['@smooth']
//!        | 'fast:' K | 'misalign:' FRAMES ['@dynamic']
//!        | 'exposure:' MS ['@' K] | 'rolling_shutter:' MS      sensor effects (need a scene)
//!        | 'distortion:' ('radtan' | 'equidistant') '(' C ',' C ',' C ',' C ')'
//! SEVERITY := 1..5 | low | mid | high                      (= 1, 3, 5)
//! ```
//!
//! Commas inside parentheses belong to their item. Whatever the written order, the pipeline
//! order is trajectory → render (with the sensor effects) → image → depth → stream; inside the image and depth groups the written order is the order applied.

use std::fmt;
use std::str::FromStr;

use rslam_core::Distortion;
use serde::{Deserialize, Serialize};

use crate::catalogue::{self, CATALOGUE};
use crate::sensor::{self, Exposure, RollingShutter, SENSOR_ITEMS};
use crate::{Group, PerturbError};

/// A parsed `--perturb` string; serialisable for the manifest, `Display` gives the canonical form.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PerturbSpec {
    /// Image corruptions in the order applied.
    pub image: Vec<FrameItem>,
    /// Depth corruptions in the order applied.
    pub depth: Vec<FrameItem>,
    /// `rot:D`: per-axis rotation deviation, degrees.
    pub rotation: Option<Deviation>,
    /// `trans:M`: per-axis translation deviation, metres.
    pub translation: Option<Deviation>,
    /// `fast:K`: keep every K-th frame.
    pub fast: Option<u32>,
    /// `misalign:D`: depth lags colour by D frames.
    pub misalign: Option<Misalign>,
    /// `exposure:MS[@K]`: motion blur of the camera's own motion.
    #[serde(default)]
    pub exposure: Option<Exposure>,
    /// `rolling_shutter:MS`: rows read out over MS milliseconds.
    #[serde(default)]
    pub rolling_shutter: Option<RollingShutter>,
    /// `distortion:MODEL(…)`: the lens the frames are seen through.
    #[serde(default)]
    pub distortion: Option<Distortion>,
}

/// One image or depth corruption of a spec.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrameItem {
    pub name: String,
    pub level: Level,
}

/// How strong a frame corruption is.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Level {
    /// Severity 1..=5; `dynamic`: each frame draws its severity uniformly from {0, …, severity}.
    Severity { severity: u8, dynamic: bool },
    /// An explicit parameter form, e.g. `depth_range:0.42-10` → [0.42, 10].
    Explicit { values: Vec<f64> },
}

/// A trajectory deviation: per-axis standard deviation, i.i.d. per pose or temporally smooth.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Deviation {
    pub sigma: f64,
    pub smooth: bool,
}

/// `misalign:D[@dynamic]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Misalign {
    pub frames: u32,
    pub dynamic: bool,
}

const TRAJECTORY_AND_STREAM: [&str; 4] = ["rot", "trans", "fast", "misalign"];

impl PerturbSpec {
    pub fn parse(text: &str) -> Result<Self, PerturbError> {
        let mut spec = PerturbSpec::default();
        let mut seen: Vec<String> = Vec::new();
        for raw in split_items(text)? {
            let item = raw.trim();
            if item.is_empty() {
                return Err(PerturbError::spec(
                    text,
                    "empty item; expected NAME:VALUE items separated by commas, e.g. fog:3,depth_missing:5",
                ));
            }
            let (name, rest) = item.split_once(':').ok_or_else(|| {
                PerturbError::spec(item, "expected NAME:VALUE, e.g. fog:3 or rot:1")
            })?;
            let name = name.trim();
            if seen.iter().any(|s| s == name) {
                return Err(PerturbError::spec(item, format!("'{name}' is given twice")));
            }
            seen.push(name.to_string());
            let (value, mode) = match rest.split_once('@') {
                Some((v, m)) => (v.trim(), Some(m.trim())),
                None => (rest.trim(), None),
            };
            spec.add(item, name, value, mode)?;
        }
        Ok(spec)
    }

    fn add(
        &mut self,
        item: &str,
        name: &str,
        value: &str,
        mode: Option<&str>,
    ) -> Result<(), PerturbError> {
        let err = |message: String| PerturbError::spec(item, message);
        match name {
            "rot" | "trans" => {
                let unit = if name == "rot" { "degrees" } else { "metres" };
                let sigma = parse_non_negative(value).ok_or_else(|| {
                    err(format!("expected a number of {unit} ≥ 0, e.g. {name}:1"))
                })?;
                let smooth = match mode {
                    None | Some("static") => false,
                    Some("smooth") => true,
                    Some(m) => return Err(err(format!("unknown mode '@{m}'; valid: @smooth"))),
                };
                let deviation = Some(Deviation { sigma, smooth });
                if name == "rot" {
                    self.rotation = deviation;
                } else {
                    self.translation = deviation;
                }
            }
            "fast" => {
                if let Some(m) = mode {
                    return Err(err(format!("fast takes no mode, got '@{m}'")));
                }
                let k = value
                    .parse::<u32>()
                    .ok()
                    .filter(|&k| k >= 1)
                    .ok_or_else(|| {
                        err("expected an integer K ≥ 1 (keep every K-th frame), e.g. fast:2".into())
                    })?;
                self.fast = Some(k);
            }
            "misalign" => {
                let frames = value.parse::<u32>().map_err(|_| {
                    err("expected a whole number of frames, e.g. misalign:10".into())
                })?;
                let dynamic = match mode {
                    None | Some("static") => false,
                    Some("dynamic") => true,
                    Some(m) => {
                        return Err(err(format!(
                            "unknown mode '@{m}'; valid: @static, @dynamic"
                        )))
                    }
                };
                self.misalign = Some(Misalign { frames, dynamic });
            }
            sensor::exposure::NAME => {
                self.exposure = Some(Exposure::parse(value, mode).map_err(err)?)
            }
            sensor::rolling_shutter::NAME => {
                self.rolling_shutter = Some(RollingShutter::parse(value, mode).map_err(err)?)
            }
            sensor::distortion::NAME => {
                self.distortion = Some(sensor::distortion::parse(value, mode).map_err(err)?)
            }
            _ => {
                let entry = catalogue::find(name).ok_or_else(|| {
                    err(format!(
                        "unknown perturbation '{name}'; valid: {}",
                        all_names().join(", ")
                    ))
                })?;
                let level = parse_level(entry, value, mode).map_err(err)?;
                let frame_item = FrameItem {
                    name: entry.name.to_string(),
                    level,
                };
                match entry.group {
                    Group::Image => self.image.push(frame_item),
                    Group::Depth => self.depth.push(frame_item),
                }
            }
        }
        Ok(())
    }

    /// True when nothing is perturbed.
    pub fn is_empty(&self) -> bool {
        *self == PerturbSpec::default()
    }

    /// True when frames must be rendered from a scene: the trajectory is deviated, or a sensor
    /// effect forms the image from the camera's motion.
    pub fn needs_scene(&self) -> bool {
        !self.scene_items().is_empty()
    }

    /// The items that need a scene, as written canonically (`rot:1`, `exposure:20`, …).
    pub fn scene_items(&self) -> Vec<String> {
        let mut items = self.deviation_items();
        items.extend(self.sensor_items());
        items
    }

    fn deviation_items(&self) -> Vec<String> {
        [("rot", self.rotation), ("trans", self.translation)]
            .into_iter()
            .filter_map(|(name, deviation)| {
                let d = deviation?;
                let mode = if d.smooth { "@smooth" } else { "" };
                Some(format!("{name}:{}{mode}", d.sigma))
            })
            .collect()
    }

    fn sensor_items(&self) -> Vec<String> {
        let exposure = self.exposure.map(|e| e.to_string());
        let rolling = self.rolling_shutter.map(|r| r.to_string());
        let lens = self.distortion.as_ref().map(sensor::distortion::item);
        exposure.into_iter().chain(rolling).chain(lens).collect()
    }

    /// Image then depth items, in the order they are applied.
    pub fn frame_items(&self) -> impl Iterator<Item = &FrameItem> {
        self.image.iter().chain(&self.depth)
    }
}

/// The items of `text`: split at the commas outside parentheses.
fn split_items(text: &str) -> Result<Vec<&str>, PerturbError> {
    let unbalanced = || {
        PerturbError::spec(
            text,
            "unbalanced parentheses; expected NAME:MODEL(a,b,…) items, e.g. distortion:radtan(-0.28,0.07,0.0002,0.00002)",
        )
    };
    let (mut items, mut start, mut depth) = (Vec::new(), 0, 0usize);
    for (i, c) in text.char_indices() {
        match c {
            '(' => depth += 1,
            ')' => depth = depth.checked_sub(1).ok_or_else(unbalanced)?,
            ',' if depth == 0 => {
                items.push(&text[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    if depth != 0 {
        return Err(unbalanced());
    }
    items.push(&text[start..]);
    Ok(items)
}

fn parse_non_negative(value: &str) -> Option<f64> {
    value
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v >= 0.0)
}

/// A severity 1..=5 or its alias (low = 1, mid = 3, high = 5).
pub fn parse_severity(value: &str) -> Option<u8> {
    match value {
        "low" => Some(1),
        "mid" => Some(3),
        "high" => Some(5),
        _ => value.parse::<u8>().ok().filter(|s| (1..=5).contains(s)),
    }
}

fn parse_level(
    entry: &crate::CatalogueEntry,
    value: &str,
    mode: Option<&str>,
) -> Result<Level, String> {
    if let Some(severity) = parse_severity(value) {
        let dynamic = match mode {
            None | Some("static") => false,
            Some("dynamic") => true,
            Some(m) => return Err(format!("unknown mode '@{m}'; valid: @static, @dynamic")),
        };
        return Ok(Level::Severity { severity, dynamic });
    }
    let severity_help = "expected a severity 1-5 or low/mid/high";
    match &entry.explicit {
        Some(form) => {
            if mode.is_some() {
                return Err(format!(
                    "an explicit parameter takes no mode; {severity_help}, or {}",
                    form.syntax
                ));
            }
            let values = (form.parse)(value)
                .map_err(|e| format!("{e}; {severity_help}, or {}", form.syntax))?;
            Ok(Level::Explicit { values })
        }
        None => Err(format!("severity '{value}': {severity_help}")),
    }
}

impl FromStr for PerturbSpec {
    type Err = PerturbError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        Self::parse(text)
    }
}

impl fmt::Display for FrameItem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.level {
            Level::Severity { severity, dynamic } => {
                write!(f, "{}:{severity}", self.name)?;
                if *dynamic {
                    write!(f, "@dynamic")?;
                }
                Ok(())
            }
            Level::Explicit { values } => {
                let form = catalogue::find(&self.name).and_then(|e| e.explicit.as_ref());
                match form {
                    Some(form) => write!(f, "{}:{}", self.name, (form.format)(values)),
                    None => write!(f, "{}:{values:?}", self.name),
                }
            }
        }
    }
}

impl fmt::Display for PerturbSpec {
    /// Canonical pipeline order: rot, trans, exposure, rolling_shutter, distortion, image
    /// items, depth items, fast, misalign.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts = self.scene_items();
        parts.extend(self.frame_items().map(|item| item.to_string()));
        if let Some(k) = self.fast {
            parts.push(format!("fast:{k}"));
        }
        if let Some(m) = self.misalign {
            let mode = if m.dynamic { "@dynamic" } else { "" };
            parts.push(format!("misalign:{}{mode}", m.frames));
        }
        write!(f, "{}", parts.join(","))
    }
}

/// Every name a spec accepts (catalogue entries, then trajectory and stream items, then sensor
/// effects).
pub fn all_names() -> Vec<&'static str> {
    CATALOGUE
        .iter()
        .map(|e| e.name)
        .chain(TRAJECTORY_AND_STREAM)
        .chain(SENSOR_ITEMS.iter().map(|e| e.name))
        .collect()
}

#[cfg(test)]
#[path = "spec_tests.rs"]
mod tests;
