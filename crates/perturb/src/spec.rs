//! The `--perturb` grammar of docs/src/perturbations.md §1:
//!
//! ```text
//! spec  := item (',' item)*
//! item  := [SENSOR ':'] NAME ':' SEVERITY ['@static' | '@dynamic']   image and depth corruptions
//!        | [SENSOR ':'] NAME ':' EXPLICIT                          e.g. depth_range:0.42-10
//!        | 'rot:' DEGREES ['@smooth'] | 'trans:' METRES ['@smooth']
//!        | 'fast:' K | 'misalign:' FRAMES ['@dynamic']
//!        | 'exposure:' MS ['@' K] | 'rolling_shutter:' MS      sensor effects (need a scene)
//!        | 'imu_noise:' K | 'imu_bias_step:' G/A | …          IMU items (see crate::imu::items)
//!        | 'baseline:' METRES ['@calibration' | '@dynamic']      calibration of a rig
//!        | [SENSOR ':'] ('extrinsic_rot:' DEGREES | 'extrinsic_trans:' METRES)
//!          ['@calibration' | '@dynamic']                       (`@dynamic`: cameras only)
//!        | 'distortion:' ('radtan' | 'equidistant') '(' C ',' C ',' C ',' C ')'
//!        | 'lights:' S | 'flicker:' HZ ['/' DEPTH] | 'daylight:' S  light items (crate::light)
//!        | 'actors:' S | 'actors:' COUNT '/' SPEED '/' NEAR            world items (crate::world)
//! SENSOR := 'cam' N | 'imu' N                               a rig's sensor: cam0, cam1, imu0
//! SEVERITY := 1..5 | low | mid | high                      (= 1, 3, 5)
//! ```
//!
//! Commas inside parentheses belong to their item. Whatever the written order, the pipeline
//! order is trajectory → render (with the sensor effects) → image → depth → stream; inside the
//! image and depth groups the written order is the order applied.
//!
//! Sensors: an image or depth item with a camera (`cam1:fog:3`) corrupts that camera's frames
//! only; without one, every camera's. A one-camera input's camera is `cam0`, so `cam0:fog:3`
//! there is `fog:3` and any other sensor is refused when the frames are perturbed
//! ([`PerturbSpec::one_camera_problem`]). An item may be given once per sensor, and not both
//! with and without a sensor (`fog:2,cam1:fog:4` is refused: write `cam0:fog:2,cam1:fog:4`).
//! Calibration items are described in [`crate::calibration`].

use std::fmt;
use std::str::FromStr;

use rslam_core::Distortion;
use serde::{Deserialize, Serialize};

use crate::applies::{ItemEntry, Setting};
use crate::calibration::{CalibrationItem, CALIBRATION_ITEMS};
use crate::catalogue::{self, CATALOGUE};
use crate::imu::{self, ImuSpec, IMU_ITEMS};
use crate::light::{self, LightSpec, LIGHT_ITEMS};
use crate::perturbation::Between;
use crate::sensor::{self, Exposure, RollingShutter, SENSOR_ITEMS};
use crate::severity::Severity;
use crate::stream::STREAM_ITEMS;
use crate::trajectory::TRAJECTORY_ITEMS;
use crate::world::{self, WorldSpec, WORLD_ITEMS};
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
    /// IMU items and `cam_imu_offset`, for rigs with an IMU.
    #[serde(default, skip_serializing_if = "ImuSpec::is_empty")]
    pub imu: ImuSpec,
    /// `baseline`, `extrinsic_rot`, `extrinsic_trans`: a rig's calibration, in the order written.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub calibration: Vec<CalibrationItem>,
    /// `distortion:MODEL(…)`: the lens the frames are seen through. Left out without one, so a
    /// job of an rslam without lenses is the same job.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distortion: Option<Distortion>,
    /// `lights`, `flicker`, `daylight`: the scene's light over time. Left out without one.
    #[serde(default, skip_serializing_if = "LightSpec::is_empty")]
    pub light: LightSpec,
    /// `actors`: what moves in the scene. Left out without one.
    #[serde(default, skip_serializing_if = "WorldSpec::is_empty")]
    pub world: WorldSpec,
}

/// One image or depth corruption of a spec.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrameItem {
    /// The camera whose frames it corrupts (`cam1`); `None`: every camera's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sensor: Option<String>,
    pub name: String,
    pub level: Level,
}

/// How strong a frame corruption is.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Level {
    /// Severity in [0, 5] (0: the clean frame); `dynamic`: each frame draws its severity
    /// uniformly from {0, …, severity} for a whole one, from [0, severity] for a real one.
    Severity { severity: Severity, dynamic: bool },
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

impl PerturbSpec {
    pub fn parse(text: &str) -> Result<Self, PerturbError> {
        let mut spec = PerturbSpec::default();
        // (sensor, name) of every item so far.
        let mut seen: Vec<(Option<String>, String)> = Vec::new();
        for raw in split_items(text)? {
            let item = raw.trim();
            if item.is_empty() {
                return Err(PerturbError::spec(
                    text,
                    "empty item; expected NAME:VALUE items separated by commas, e.g. fog:3,depth_missing:5",
                ));
            }
            let expected = || PerturbError::spec(item, "expected NAME:VALUE, e.g. fog:3 or rot:1");
            let (first, rest) = item.split_once(':').ok_or_else(expected)?;
            let (sensor, name, rest) = if is_sensor_name(first.trim()) {
                let (name, rest) = rest.split_once(':').ok_or_else(|| {
                    PerturbError::spec(item, "expected SENSOR:NAME:VALUE, e.g. cam1:fog:3")
                })?;
                (Some(first.trim()), name.trim(), rest)
            } else {
                (None, first.trim(), rest)
            };
            check_once(item, sensor, name, &seen)?;
            seen.push((sensor.map(str::to_string), name.to_string()));
            let (value, mode) = match rest.split_once('@') {
                Some((v, m)) => (v.trim(), Some(m.trim())),
                None => (rest.trim(), None),
            };
            spec.add(item, sensor, name, value, mode)?;
        }
        Ok(spec)
    }

    fn add(
        &mut self,
        item: &str,
        sensor: Option<&str>,
        name: &str,
        value: &str,
        mode: Option<&str>,
    ) -> Result<(), PerturbError> {
        let err = |message: String| PerturbError::spec(item, message);
        if CALIBRATION_ITEMS.iter().any(|e| e.name == name) {
            let parsed = CalibrationItem::parse(sensor, name, value, mode).map_err(err)?;
            self.calibration.push(parsed);
            return Ok(());
        }
        let known = |name: &str| catalogue::find(name).is_some() || all_names().contains(&name);
        if let Some(sensor) = sensor.filter(|_| known(name)) {
            if catalogue::find(name).is_none() {
                return Err(err(format!(
                    "'{name}' applies to the whole rig and takes no sensor; per-sensor items: image and depth corruptions, extrinsic_rot, extrinsic_trans"
                )));
            }
            if !sensor.starts_with("cam") {
                return Err(err(format!(
                    "'{name}' corrupts a camera's frames; expected a camera (cam0, cam1, …), not {sensor}"
                )));
            }
        }
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
            name if imu::is_imu_item(name) => self.imu.add(name, value, mode).map_err(err)?,
            name if light::is_light_item(name) => self.light.add(name, value, mode).map_err(err)?,
            name if world::is_world_item(name) => self.world.add(name, value, mode).map_err(err)?,
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
                    sensor: sensor.map(str::to_string),
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

    /// The items that decide where and when frames are seen (trajectory deviations, `fast`, a
    /// rig's calibration) without those that change what a frame shows: the spec of the clean
    /// frames at a perturbed sequence's ground-truth poses.
    pub fn poses_only(&self) -> PerturbSpec {
        PerturbSpec {
            rotation: self.rotation,
            translation: self.translation,
            fast: self.fast,
            calibration: self.calibration.clone(),
            ..PerturbSpec::default()
        }
    }

    /// The spec of a camera without depth: no depth items, no `misalign`.
    pub fn without_depth(&self) -> PerturbSpec {
        PerturbSpec {
            depth: Vec::new(),
            misalign: None,
            ..self.clone()
        }
    }

    /// This spec without its image items: for a camera that sees only depth.
    pub fn without_image(&self) -> PerturbSpec {
        PerturbSpec {
            image: Vec::new(),
            ..self.clone()
        }
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
        items.extend(self.light.items());
        items.extend(self.world.items());
        items
    }

    pub(crate) fn deviation_items(&self) -> Vec<String> {
        [("rot", self.rotation), ("trans", self.translation)]
            .into_iter()
            .filter_map(|(name, deviation)| {
                let d = deviation?;
                let mode = if d.smooth { "@smooth" } else { "" };
                Some(format!("{name}:{}{mode}", d.sigma))
            })
            .collect()
    }

    pub(crate) fn sensor_items(&self) -> Vec<String> {
        let exposure = self.exposure.map(|e| e.to_string());
        let rolling = self.rolling_shutter.map(|r| r.to_string());
        let lens = self.distortion.as_ref().map(sensor::distortion::item);
        exposure.into_iter().chain(rolling).chain(lens).collect()
    }

    /// Image then depth items, in the order they are applied.
    pub fn frame_items(&self) -> impl Iterator<Item = &FrameItem> {
        self.image.iter().chain(&self.depth)
    }

    /// The first frame item that carries a state from frame to frame (auto_exposure), if any:
    /// its frames must run in capture order from the first, and a resumed run redoes them all.
    pub fn stateful_item(&self) -> Option<&FrameItem> {
        self.frame_items()
            .find(|item| crate::catalogue::find(&item.name).is_some_and(|e| e.carries_state()))
    }

    /// The spec camera `camera` of a rig applies to its frames: the image and depth items for
    /// every camera and for it (no longer addressed), every item of the whole rig, and no
    /// calibration items (the rig has placed the cameras already).
    pub fn for_camera(&self, camera: &str) -> PerturbSpec {
        let own = |items: &[FrameItem]| -> Vec<FrameItem> {
            items
                .iter()
                .filter(|i| i.sensor.as_deref().is_none_or(|s| s == camera))
                .map(|i| FrameItem {
                    sensor: None,
                    ..i.clone()
                })
                .collect()
        };
        PerturbSpec {
            image: own(&self.image),
            depth: own(&self.depth),
            calibration: Vec::new(),
            ..self.clone()
        }
    }

    /// `fast` and `misalign`, as written canonically.
    pub(crate) fn stream_items(&self) -> Vec<String> {
        let fast = self.fast.map(|k| format!("fast:{k}"));
        let misalign = self.misalign.map(|m| {
            let mode = if m.dynamic { "@dynamic" } else { "" };
            format!("misalign:{}{mode}", m.frames)
        });
        fast.into_iter().chain(misalign).collect()
    }

    /// The first item addressed to a sensor not in `sensors` (`cam0`, `cam1`, `imu0`, …), with
    /// the message for it.
    pub fn unknown_sensor(&self, sensors: &[&str]) -> Option<PerturbError> {
        let addressed = self
            .frame_items()
            .filter_map(|i| Some((i.sensor.as_deref()?, i.to_string())))
            .chain(
                self.calibration
                    .iter()
                    .filter_map(|i| Some((i.sensor.as_deref()?, i.to_string()))),
            );
        for (sensor, item) in addressed {
            if !sensors.contains(&sensor) {
                return Some(PerturbError::spec(
                    item,
                    crate::applies::no_such_sensor(sensor, sensors),
                ));
            }
        }
        None
    }

    /// Why this spec cannot perturb the frames of one camera: a calibration item, or an item
    /// addressed to a sensor other than `cam0`, that one camera. What else the frames take is
    /// their job's to say ([`PerturbSpec::refusal`]).
    pub fn one_camera_problem(&self) -> Option<PerturbError> {
        self.refusal(&Setting::any_one_camera())
    }
}

/// `cam` or `imu` followed by a number: the name of a rig's sensor.
fn is_sensor_name(text: &str) -> bool {
    ["cam", "imu"].iter().any(|prefix| {
        text.strip_prefix(prefix)
            .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
    })
}

/// Refuses an item given twice for the same sensor, or both for every camera and for one.
fn check_once(
    item: &str,
    sensor: Option<&str>,
    name: &str,
    seen: &[(Option<String>, String)],
) -> Result<(), PerturbError> {
    // An item without a sensor covers every camera (an IMU only when named).
    let covers = |every: Option<&str>, one: Option<&str>| {
        every.is_none() && one.is_some_and(|s| s.starts_with("cam"))
    };
    let clash = seen.iter().find(|(s, n)| {
        n == name
            && (s.as_deref() == sensor
                || covers(s.as_deref(), sensor)
                || covers(sensor, s.as_deref()))
    });
    match clash {
        None => Ok(()),
        Some((s, _)) if s.as_deref() == sensor => {
            Err(PerturbError::spec(item, format!("'{name}' is given twice")))
        }
        Some(_) => Err(PerturbError::spec(
            item,
            format!("'{name}' is given for every camera and for one; give it per camera instead, e.g. cam0:{name}:…,cam1:{name}:…"),
        )),
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
    if let Some(severity) = Severity::parse(value) {
        if let (None, Between::WholeOnly(why)) = (severity.as_whole(), entry.between) {
            return Err(format!(
                "severity {severity}: {} takes whole severities 0-5 only ({why})",
                entry.name
            ));
        }
        let dynamic = match mode {
            None | Some("static") => false,
            Some("dynamic") => true,
            Some(m) => return Err(format!("unknown mode '@{m}'; valid: @static, @dynamic")),
        };
        return Ok(Level::Severity { severity, dynamic });
    }
    let severity_help =
        "expected a severity 0-5 (real ones like 2.5 too, at most two decimals) or low/mid/high";
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
        if let Some(sensor) = &self.sensor {
            write!(f, "{sensor}:")?;
        }
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
    /// Canonical pipeline order: calibration items, rot, trans, exposure, rolling_shutter,
    /// distortion, light items, world items, image items, depth items, fast, misalign, IMU items.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts: Vec<String> = self.calibration.iter().map(|i| i.to_string()).collect();
        parts.extend(self.scene_items());
        parts.extend(self.frame_items().map(|item| item.to_string()));
        parts.extend(self.stream_items());
        parts.extend(self.imu.items());
        write!(f, "{}", parts.join(","))
    }
}

/// The entries of every item that is not a frame corruption, in the order `rslam list` shows
/// them: trajectory, stream, sensor, light, world, calibration, IMU.
pub const ITEM_TABLES: [(&str, &[ItemEntry]); 7] = [
    ("trajectory", TRAJECTORY_ITEMS),
    ("stream", STREAM_ITEMS),
    ("sensor", SENSOR_ITEMS),
    ("light", LIGHT_ITEMS),
    ("world", WORLD_ITEMS),
    ("calibration", CALIBRATION_ITEMS),
    ("imu", IMU_ITEMS),
];

/// Every name a spec accepts (catalogue entries, then the other items of [`ITEM_TABLES`]).
pub fn all_names() -> Vec<&'static str> {
    CATALOGUE
        .iter()
        .map(|e| e.name)
        .chain(
            ITEM_TABLES
                .iter()
                .flat_map(|(_, t)| t.iter().map(|e| e.name)),
        )
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        PerturbSpec::parse(text).unwrap_err().to_string()
    }

    #[test]
    fn parses_every_item_kind_into_its_group() {
        let spec = PerturbSpec::parse(
            "gaussian_noise:2,depth_missing:5,rot:1,trans:0.025@smooth,fast:2,misalign:10@dynamic,brightness:high@dynamic,depth_range:0.42-10",
        )
        .unwrap();
        let names: Vec<&str> = spec.image.iter().map(|i| i.name.as_str()).collect();
        assert_eq!(names, ["gaussian_noise", "brightness"]);
        assert_eq!(
            spec.image[1].level,
            Level::Severity {
                severity: Severity::whole(5).unwrap(),
                dynamic: true
            }
        );
        assert_eq!(
            spec.depth[0].level,
            Level::Severity {
                severity: Severity::whole(5).unwrap(),
                dynamic: false
            }
        );
        assert_eq!(
            spec.depth[1].level,
            Level::Explicit {
                values: vec![0.42, 10.0]
            }
        );
        assert_eq!(
            spec.rotation,
            Some(Deviation {
                sigma: 1.0,
                smooth: false
            })
        );
        assert_eq!(
            spec.translation,
            Some(Deviation {
                sigma: 0.025,
                smooth: true
            })
        );
        assert_eq!(spec.fast, Some(2));
        assert_eq!(
            spec.misalign,
            Some(Misalign {
                frames: 10,
                dynamic: true
            })
        );
        assert!(spec.needs_scene());
    }

    #[test]
    fn aliases_map_to_severities() {
        for (alias, severity) in [("low", 1), ("mid", 3), ("high", 5), ("4", 4)] {
            let spec = PerturbSpec::parse(&format!("contrast:{alias}")).unwrap();
            assert_eq!(
                spec.image[0].level,
                Level::Severity {
                    severity: Severity::whole(severity).unwrap(),
                    dynamic: false
                }
            );
        }
    }

    #[test]
    fn real_severities_parse_where_the_item_interpolates() {
        let spec =
            PerturbSpec::parse("fog:2.5@dynamic,gaussian_noise:0,depth_missing:0.75").unwrap();
        let real = |hundredths| Severity::from_hundredths(hundredths).unwrap();
        assert_eq!(
            spec.image[0].level,
            Level::Severity {
                severity: real(250),
                dynamic: true
            }
        );
        assert_eq!(
            spec.image[1].level.clone(),
            Level::Severity {
                severity: Severity::CLEAN,
                dynamic: false
            }
        );
        assert_eq!(
            spec.to_string(),
            "fog:2.5@dynamic,gaussian_noise:0,depth_missing:0.75"
        );
        assert_eq!(PerturbSpec::parse(&spec.to_string()).unwrap(), spec);
        let json = serde_json::to_string(&spec).unwrap();
        assert!(json.contains(r#""severity":2.5"#), "{json}");
        assert_eq!(serde_json::from_str::<PerturbSpec>(&json).unwrap(), spec);
        let e = err("saturate:2.5");
        assert!(
            e.contains("'saturate:2.5'")
                && e.contains("whole severities")
                && e.contains("desaturating"),
            "{e}"
        );
        let e = err("fog:2.125");
        assert!(e.contains("at most two decimals"), "{e}");
    }

    #[test]
    fn display_is_canonical_and_round_trips() {
        let spec = PerturbSpec::parse(
            " misalign:5 , depth_range:0.42-10,pixelate:mid@static,rot:3@smooth,gaussian_noise:1@dynamic,fast:4,trans:0.05",
        )
        .unwrap();
        let text = spec.to_string();
        assert_eq!(
            text,
            "rot:3@smooth,trans:0.05,pixelate:3,gaussian_noise:1@dynamic,depth_range:0.42-10,fast:4,misalign:5"
        );
        assert_eq!(PerturbSpec::parse(&text).unwrap(), spec);
        let json = serde_json::to_string(&spec).unwrap();
        assert_eq!(serde_json::from_str::<PerturbSpec>(&json).unwrap(), spec);
    }

    #[test]
    fn bad_items_are_named_with_the_valid_choices() {
        let e = err("fgo:3");
        assert!(
            e.contains("'fgo:3'") && e.contains("gaussian_noise") && e.contains("misalign"),
            "{e}"
        );
        let e = err("brightness:6");
        assert!(
            e.contains("'brightness:6'") && e.contains("0-5") && e.contains("low/mid/high"),
            "{e}"
        );
        let e = err("brightness:3@sometimes");
        assert!(e.contains("@dynamic"), "{e}");
        let e = err("depth_range:5-1");
        assert!(
            e.contains("MIN < MAX") && e.contains("depth_range:0.42-10"),
            "{e}"
        );
        let e = err("depth_range:0.4-3@dynamic");
        assert!(e.contains("no mode"), "{e}");
        assert!(err("brightness").contains("NAME:VALUE"));
        assert!(err("brightness:1,,fast:2").contains("empty item"));
        assert!(err("").contains("empty item"));
        assert!(err("fast:0").contains("K ≥ 1"));
        assert!(err("fast:2@dynamic").contains("no mode"));
        assert!(err("rot:-1").contains("degrees"));
        assert!(err("trans:x").contains("metres"));
        assert!(err("rot:1@dynamic").contains("@smooth"));
        assert!(err("misalign:2.5").contains("whole number"));
        assert!(err("brightness:1,brightness:2").contains("twice"));
    }

    #[test]
    fn every_catalogue_entry_parses_at_every_severity() {
        for name in all_names() {
            if crate::find(name).is_some() {
                for severity in 1..=5 {
                    PerturbSpec::parse(&format!("{name}:{severity}@dynamic")).unwrap();
                }
            }
        }
    }

    /// Found by fuzzing: an item holding a line break was quoted as is, and the error spanned lines.
    #[test]
    fn errors_quote_line_breaks_as_escapes() {
        let err = PerturbSpec::parse("fog:3,depth_range:x\r2")
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("spec item 'depth_range:x\\r2': "), "{err}");
        let err = PerturbSpec::parse("fo\ng:3").unwrap_err().to_string();
        assert!(
            err.starts_with("spec item 'fo\\ng:3': unknown perturbation 'fo\\ng'"),
            "{err}"
        );
    }

    #[test]
    fn sensor_items_parse_need_a_scene_and_print_in_pipeline_order() {
        let spec = PerturbSpec::parse("fog:2,rolling_shutter:30,exposure:20@8").unwrap();
        assert_eq!(
            spec.exposure,
            Some(Exposure {
                ms: 20.0,
                subframes: Some(8)
            })
        );
        assert_eq!(spec.rolling_shutter, Some(RollingShutter { ms: 30.0 }));
        assert!(spec.needs_scene());
        assert_eq!(spec.scene_items(), ["exposure:20@8", "rolling_shutter:30"]);
        assert_eq!(spec.to_string(), "exposure:20@8,rolling_shutter:30,fog:2");
        assert_eq!(PerturbSpec::parse(&spec.to_string()).unwrap(), spec);
        let e = err("exposure:20@0");
        assert!(
            e.contains("exposure:20@0") && e.contains("sub-frame count"),
            "{e}"
        );
        assert!(err("rolling_shutter:fast").contains("milliseconds"));
        assert!(
            err("nope:1").contains("rolling_shutter"),
            "sensor names are listed"
        );
    }

    #[test]
    fn imu_items_go_to_their_own_field_print_last_and_round_trip() {
        let spec = PerturbSpec::parse(
            "cam_imu_offset:-3,fog:2,imu_jitter:0.2,imu_noise:2,imu_drop:0.01/5",
        )
        .unwrap();
        assert_eq!(spec.imu.noise_scale, Some(2.0));
        assert_eq!(spec.imu.cam_imu_offset_ms, Some(-3.0));
        assert_eq!(spec.image.len(), 1);
        assert!(!spec.needs_scene());
        assert_eq!(
            spec.to_string(),
            "fog:2,imu_noise:2,imu_drop:0.01/5,imu_jitter:0.2,cam_imu_offset:-3"
        );
        assert_eq!(PerturbSpec::parse(&spec.to_string()).unwrap(), spec);
        let json = serde_json::to_string(&spec).unwrap();
        assert_eq!(serde_json::from_str::<PerturbSpec>(&json).unwrap(), spec);
        // Specs without IMU items serialise as before (manifests of earlier runs stay the same).
        let plain = serde_json::to_string(&PerturbSpec::parse("fog:2").unwrap()).unwrap();
        assert!(!plain.contains("imu"), "{plain}");
        assert!(!plain.contains("distortion"), "{plain}");
        assert!(!plain.contains("calibration"), "{plain}");
        let e = err("imu_saturation:2");
        assert!(
            e.starts_with("spec item 'imu_saturation:2': '2': expected GYRO/ACC"),
            "{e}"
        );
        assert!(err("imu_noise:1,imu_noise:2").contains("twice"));
        assert!(
            err("nope:1").contains("cam_imu_offset"),
            "IMU names are listed"
        );
    }

    #[test]
    fn items_addressed_to_a_camera_reach_only_that_camera() {
        let spec =
            PerturbSpec::parse("cam1:fog:3,gaussian_noise:2,cam0:motion_blur:2@dynamic").unwrap();
        assert_eq!(spec.image[0].sensor.as_deref(), Some("cam1"));
        assert_eq!(spec.image[1].sensor, None);
        let names =
            |s: &PerturbSpec| -> Vec<String> { s.image.iter().map(|i| i.to_string()).collect() };
        // Written order kept, the sensor dropped.
        assert_eq!(
            names(&spec.for_camera("cam0")),
            ["gaussian_noise:2", "motion_blur:2@dynamic"]
        );
        assert_eq!(
            names(&spec.for_camera("cam1")),
            ["fog:3", "gaussian_noise:2"]
        );
        assert_eq!(names(&spec.for_camera("cam2")), ["gaussian_noise:2"]);
        assert_eq!(
            spec.to_string(),
            "cam1:fog:3,gaussian_noise:2,cam0:motion_blur:2@dynamic"
        );
        assert_eq!(PerturbSpec::parse(&spec.to_string()).unwrap(), spec);
        let json = serde_json::to_string(&spec).unwrap();
        assert_eq!(serde_json::from_str::<PerturbSpec>(&json).unwrap(), spec);
        // An unaddressed spec serialises as before the sensor field existed.
        let plain = serde_json::to_string(&PerturbSpec::parse("fog:3").unwrap()).unwrap();
        assert!(
            !plain.contains("sensor") && !plain.contains("calibration"),
            "{plain}"
        );
    }

    #[test]
    fn calibration_items_parse_with_their_modes_and_round_trip() {
        let spec = PerturbSpec::parse(
            "fog:1,baseline:0.01@dynamic,cam1:extrinsic_rot:0.5@calibration,imu0:extrinsic_trans:0.01,extrinsic_trans:0.002,cam0:extrinsic_rot:0.5@dynamic",
        )
        .unwrap();
        use crate::calibration::CalibrationMode::{Calibration, Rendered};
        let got: Vec<(Option<&str>, &str, f64, _, bool)> = spec
            .calibration
            .iter()
            .map(|i| {
                (
                    i.sensor.as_deref(),
                    i.name.as_str(),
                    i.sigma,
                    i.mode,
                    i.dynamic,
                )
            })
            .collect();
        assert_eq!(
            got,
            [
                (None, "baseline", 0.01, Rendered, true),
                (Some("cam1"), "extrinsic_rot", 0.5, Calibration, false),
                (Some("imu0"), "extrinsic_trans", 0.01, Rendered, false),
                (None, "extrinsic_trans", 0.002, Rendered, false),
                (Some("cam0"), "extrinsic_rot", 0.5, Rendered, true),
            ]
        );
        assert_eq!(
            spec.to_string(),
            "baseline:0.01@dynamic,cam1:extrinsic_rot:0.5@calibration,imu0:extrinsic_trans:0.01,extrinsic_trans:0.002,cam0:extrinsic_rot:0.5@dynamic,fog:1"
        );
        assert_eq!(PerturbSpec::parse(&spec.to_string()).unwrap(), spec);
        let every_camera = PerturbSpec::parse("extrinsic_trans:0.01@dynamic").unwrap();
        assert!(
            every_camera.calibration[0].dynamic && every_camera.calibration[0].sensor.is_none()
        );
        assert_eq!(every_camera.to_string(), "extrinsic_trans:0.01@dynamic");
        assert!(!spec.needs_scene());
        assert!(spec.for_camera("cam0").calibration.is_empty());
    }

    #[test]
    fn sensor_and_calibration_errors_name_the_item_and_what_was_expected() {
        let e = err("cam1:rot:1");
        assert!(
            e.starts_with("spec item 'cam1:rot:1': 'rot' applies to the whole rig"),
            "{e}"
        );
        let e = err("imu0:fog:3");
        assert!(
            e.contains("expected a camera (cam0, cam1, …), not imu0"),
            "{e}"
        );
        assert!(err("cam1:fog").contains("SENSOR:NAME:VALUE"));
        assert!(err("cam1:fgo:3").contains("unknown perturbation 'fgo'"));
        assert!(err("cam1:fog:3,cam1:fog:2").contains("'fog' is given twice"));
        let e = err("fog:2,cam1:fog:4");
        assert!(
            e.contains("for every camera and for one") && e.contains("cam0:fog:"),
            "{e}"
        );
        PerturbSpec::parse("cam0:fog:2,cam1:fog:4").unwrap();
        assert!(err("cam1:baseline:0.01").contains("takes no sensor"));
        assert!(err("baseline:-0.01").contains("metres ≥ 0"));
        assert!(err("extrinsic_rot:x").contains("degrees ≥ 0"));
        let e = err("imu0:extrinsic_rot:1@dynamic");
        assert!(
            e.starts_with("spec item 'imu0:extrinsic_rot:1@dynamic': @dynamic moves a camera")
                && e.ends_with("use imu0:extrinsic_rot:1 (once per sequence)"),
            "{e}"
        );
        for text in [
            "cam1:extrinsic_trans:0.01@dynamic@calibration",
            "baseline:0.01@calibration@dynamic",
        ] {
            let e = err(text);
            assert!(
                e.contains("@dynamic and @calibration exclude each other"),
                "{e}"
            );
        }
        assert!(err("extrinsic_rot:1@smooth").contains("valid: @calibration, @dynamic"));
        assert!(err("baseline:0.1@smooth").contains("@calibration, @dynamic"));
        assert!(err("baseline:0.01,baseline:0.02@calibration").contains("twice"));
        for text in ["cam1:fog:3", "baseline:0.01", "cam0:extrinsic_rot:1"] {
            assert!(!err(text.split(':').next().unwrap()).contains('\n'));
        }
    }

    #[test]
    fn a_one_camera_input_takes_cam0_items_and_refuses_other_sensors_and_calibration() {
        let one = |text: &str| {
            PerturbSpec::parse(text)
                .unwrap()
                .one_camera_problem()
                .map(|e| e.to_string())
        };
        assert_eq!(one("cam0:fog:3,gaussian_noise:1"), None);
        let e = one("gaussian_noise:1,cam1:fog:3").unwrap();
        assert!(
            e.starts_with("spec item 'cam1:fog:3': this input has one camera, cam0"),
            "{e}"
        );
        let e = one("baseline:0.01@calibration").unwrap();
        assert!(
            e.starts_with("spec item 'baseline:0.01@calibration': a calibration item needs a rig"),
            "{e}"
        );
        let spec = PerturbSpec::parse("cam2:fog:1,imu0:extrinsic_rot:1").unwrap();
        let e = spec.unknown_sensor(&["cam0", "cam1"]).unwrap().to_string();
        assert_eq!(
            e,
            "spec item 'cam2:fog:1': no sensor 'cam2' here; the sensors are cam0, cam1"
        );
        let e = spec
            .unknown_sensor(&["cam0", "cam1", "cam2"])
            .unwrap()
            .to_string();
        assert!(
            e.contains("'imu0:extrinsic_rot:1': no sensor 'imu0'"),
            "{e}"
        );
        assert!(spec
            .unknown_sensor(&["cam0", "cam1", "cam2", "imu0"])
            .is_none());
    }

    #[test]
    fn distortion_keeps_its_commas_and_round_trips() {
        let spec =
            PerturbSpec::parse("fog:2, distortion:radtan(-0.28, 0.07,2e-4,-3e-5),exposure:20")
                .unwrap();
        assert_eq!(
            spec.distortion,
            Some(rslam_core::Distortion::Radtan {
                k1: -0.28,
                k2: 0.07,
                p1: 2e-4,
                p2: -3e-5
            })
        );
        assert_eq!(spec.image.len(), 1);
        assert!(spec.needs_scene());
        assert_eq!(
            spec.to_string(),
            "exposure:20,distortion:radtan(-0.28,0.07,0.0002,-0.00003),fog:2"
        );
        assert_eq!(PerturbSpec::parse(&spec.to_string()).unwrap(), spec);
        let fisheye =
            PerturbSpec::parse("distortion:equidistant(0.1,-0.02,0.003,-0.0004)").unwrap();
        assert!(matches!(
            fisheye.distortion,
            Some(rslam_core::Distortion::Equidistant { k4, .. }) if k4 == -0.0004
        ));
        for (bad, says) in [
            ("distortion:radtan(1,2,3)", "3 coefficients"),
            ("distortion:radtan(1,2,3,4", "unbalanced parentheses"),
            ("distortion:radtan(1,2,3,4))", "unbalanced parentheses"),
            (
                "distortion:pinhole(1,2,3,4)",
                "unknown lens model 'pinhole'",
            ),
            ("distortion:radtan(1,2,3,4)@x", "takes no mode"),
            ("distortion:3", "expected radtan(k1,k2,p1,p2)"),
        ] {
            let e = err(bad);
            assert!(e.contains(says) && !e.contains('\n'), "{bad}: {e}");
        }
        assert!(
            err("distortion:radtan(1,x,3,4)").starts_with("spec item 'distortion:radtan(1,x,3,4)'")
        );
    }
}
