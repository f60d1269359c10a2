//! Where each spec item applies. Every item declares what it needs of a job ([`Need`]: a scene
//! to render, depth, an IMU, a rig, a sequence in time, …), in its catalogue entry
//! ([`crate::CatalogueEntry::needs`]) or its [`ItemEntry`]; a job states what it has
//! ([`Setting`]); [`PerturbSpec::refusal`] is the one "is this item allowed here", naming the
//! first item refused and why.

use rslam_core::Distortion;

use crate::calibration::CalibrationMode;
use crate::spec::{PerturbSpec, ITEM_TABLES};
use crate::{catalogue, PerturbError};

/// What an item needs of the job it is given to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Need {
    /// Moves one sensor against the others: a rig of several sensors.
    Rig,
    /// Forms the frames from the sensors' poses: a scene to render, not recorded frames.
    Scene,
    /// Acts on a sequence of frames in time (which frame goes where, and when).
    Sequence,
    /// Plays the sequence faster than it was captured.
    SpeedUp,
    /// Gives the frames new timestamps.
    NewStamps,
    /// Corrupts or delays a depth stream.
    Depth,
    /// A lens the layout's calibration files can state ([`Lenses`]).
    Lens,
    /// Carries a state from frame to frame: frames in capture order from the first.
    CaptureOrder,
    /// Reads or changes an IMU's stream.
    Imu,
    /// Changes a scene's lights: a built-in scene, whose light is kept as layers.
    LightLayers,
    /// Places people and objects on a scene's free floor: a built-in scene, which knows it.
    FreeFloor,
}

impl Need {
    /// A few words for `rslam list`: what the item needs.
    pub fn words(self) -> &'static str {
        match self {
            Need::Rig => "a rig",
            Need::Scene => "a scene",
            Need::Sequence => "a sequence",
            Need::SpeedUp => "playback faster than capture",
            Need::NewStamps => "frames that can take new stamps",
            Need::Depth => "depth",
            Need::Lens => "a layout that states the lens",
            Need::CaptureOrder => "frames in capture order",
            Need::Imu => "an IMU",
            Need::LightLayers => "a built-in scene (its lights as layers)",
            Need::FreeFloor => "a built-in scene (its free floor)",
        }
    }
}

/// The lens models a layout's calibration files can state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lenses {
    /// Radial-tangential and equidistant (the one-camera layouts' cam_params.json and settings).
    Any,
    /// Radial-tangential only (EuRoC's sensor.yaml and ORB-SLAM3's stereo settings).
    Radtan,
    /// None yet.
    None,
}

/// What a job offers the spec's items: everything but what it lacks.
#[derive(Clone, Debug, PartialEq)]
pub struct Setting {
    /// The job's input, for messages: "a one-camera render", "the 'stereo' rig", …
    pub input: String,
    /// The sensors an item may name: `cam0` for one camera; a rig's cameras and IMU.
    pub sensors: Vec<String>,
    /// What it lacks, each with the clause that says why ("an image input has none").
    pub lacks: Vec<(Need, String)>,
    pub lenses: Lenses,
}

impl Setting {
    /// A setting of `input` with `sensors` that lacks nothing yet.
    pub fn new(input: impl Into<String>, sensors: &[&str]) -> Self {
        Setting {
            input: input.into(),
            sensors: sensors.iter().map(|s| s.to_string()).collect(),
            lacks: Vec::new(),
            lenses: Lenses::Any,
        }
    }

    /// One camera, `cam0`, of `input`: no rig.
    pub fn one_camera(input: impl Into<String>) -> Self {
        let setting = Self::new(input, &["cam0"]);
        let clause = format!("{} has one camera", setting.input);
        setting.lacking(Need::Rig, clause)
    }

    /// One camera that takes every item but those for other sensors or a rig: what a
    /// [`crate::Perturber`], given one camera's frames, checks.
    pub fn any_one_camera() -> Self {
        Self::one_camera("this input")
    }

    /// This setting, lacking `need` for the reason `clause`.
    pub fn lacking(mut self, need: Need, clause: impl Into<String>) -> Self {
        self.lacks.push((need, clause.into()));
        self
    }

    /// This setting, lacking each of `needs` for the plain reason: its input "has none", "holds
    /// no scene", "is not a sequence" or "takes frames in any order".
    pub fn lacking_all(self, needs: &[Need]) -> Self {
        needs.iter().fold(self, |setting, &need| {
            let clause = match need {
                Need::Scene => format!("{} holds no scene", setting.input),
                Need::Sequence => format!("{} is not a sequence", setting.input),
                Need::CaptureOrder => format!("{} takes frames in any order", setting.input),
                _ => format!("{} has none", setting.input),
            };
            setting.lacking(need, clause)
        })
    }

    pub fn with_lenses(self, lenses: Lenses) -> Self {
        Setting { lenses, ..self }
    }

    /// Why it lacks `need`, where it does.
    fn lack(&self, need: Need, spec: &PerturbSpec) -> Option<&str> {
        if need == Need::Lens {
            let fits = match (self.lenses, &spec.distortion) {
                (Lenses::Any, _) | (_, None) => true,
                (Lenses::Radtan, Some(lens)) => matches!(lens, Distortion::Radtan { .. }),
                (Lenses::None, Some(_)) => false,
            };
            return (!fits).then_some("");
        }
        self.lacks
            .iter()
            .find(|(lacked, _)| *lacked == need)
            .map(|(_, clause)| clause.as_str())
    }
}

/// The standard entry of an item that is not a frame corruption: trajectory, stream, sensor,
/// calibration and IMU items.
pub struct ItemEntry {
    pub name: &'static str,
    /// How to write it in a spec.
    pub syntax: &'static str,
    /// One line on what it does, for `rslam list`.
    pub description: &'static str,
    /// What it needs of a job, checked in this order.
    pub needs: &'static [Need],
}

/// An item of a spec as the check sees it.
struct Written {
    /// As written canonically, e.g. `cam1:fog:3`.
    text: String,
    name: String,
    /// The sensor it is addressed to, if any.
    sensor: Option<String>,
    needs: Vec<Need>,
}

impl PerturbSpec {
    /// Why `setting` cannot take this spec: the first item (in canonical order) that names a
    /// sensor it does not have or needs what it lacks, with the reason; `None` when it takes all.
    pub fn refusal(&self, setting: &Setting) -> Option<PerturbError> {
        self.written().into_iter().find_map(|item| {
            let reason = match &item.sensor {
                Some(sensor) if !setting.sensors.contains(sensor) => {
                    let sensors: Vec<&str> = setting.sensors.iter().map(String::as_str).collect();
                    no_such_sensor(sensor, &sensors)
                }
                _ => item.needs.iter().find_map(|&need| {
                    let clause = setting.lack(need, self)?;
                    Some(missing(need, &item, clause, setting))
                })?,
            };
            Some(PerturbError::spec(item.text, reason))
        })
    }

    /// Every item in canonical order, with what it needs.
    fn written(&self) -> Vec<Written> {
        let calibration = self.calibration.iter().map(|i| Written {
            text: i.to_string(),
            name: i.name.clone(),
            sensor: i.sensor.clone(),
            needs: match i.mode {
                CalibrationMode::Rendered => needs(&i.name),
                CalibrationMode::Calibration => vec![Need::Rig],
            },
        });
        let frame = self.frame_items().map(|i| Written {
            text: i.to_string(),
            name: i.name.clone(),
            sensor: i.sensor.clone(),
            needs: needs(&i.name),
        });
        let whole_rig = |text: String| {
            let name = text.split(':').next().unwrap_or_default().to_string();
            Written {
                needs: needs(&name),
                text,
                name,
                sensor: None,
            }
        };
        let before_frames = [
            self.deviation_items(),
            self.sensor_items(),
            self.light.items(),
            self.world.items(),
        ]
        .concat();
        let after_frames = [self.stream_items(), self.imu.items()].concat();
        calibration
            .chain(before_frames.into_iter().map(whole_rig))
            .chain(frame)
            .chain(after_frames.into_iter().map(whole_rig))
            .collect()
    }
}

/// What the item `name` needs, from its entry.
fn needs(name: &str) -> Vec<Need> {
    let other = ITEM_TABLES
        .iter()
        .flat_map(|(_, table)| table.iter())
        .find(|e| e.name == name);
    match other {
        Some(entry) => entry.needs.to_vec(),
        None => catalogue::find(name).map(|e| e.needs()).unwrap_or_default(),
    }
}

/// Why an item cannot name `sensor` where the sensors are `sensors`.
pub(crate) fn no_such_sensor(sensor: &str, sensors: &[&str]) -> String {
    match sensors {
        [one] => format!("this input has one camera, {one}: address it as {one} or give no sensor (other sensors need a rig)"),
        _ => format!("no sensor '{sensor}' here; the sensors are {}", sensors.join(", ")),
    }
}

/// Why `item` cannot be given where the setting lacks `need`, for the reason `clause`.
fn missing(need: Need, item: &Written, clause: &str, setting: &Setting) -> String {
    let name = &item.name;
    match need {
        Need::Rig => format!("a calibration item needs a rig (a rig render, or a recorded EuRoC dataset), and {clause}"),
        Need::Scene if item.needs.contains(&Need::Rig) => {
            let base = item.text.split('@').next().unwrap_or(&item.text);
            format!("a recorded dataset cannot be re-rendered with a moved sensor; perturb its written calibration instead: {base}@calibration")
        }
        Need::Scene => format!("{name} forms the frames from the camera's poses and needs a scene to render, and {clause}: render a scene with it instead"),
        Need::Sequence => format!("{name} acts on a sequence of frames in time, and {clause}: perturb a dataset or render a scene with it instead"),
        Need::SpeedUp => format!("{name} plays the sequence faster than it was captured, and {clause}"),
        Need::NewStamps => format!("{name} gives the frames new timestamps, and {clause}"),
        Need::Depth if name == "misalign" => format!("misalign delays depth against colour, and {clause} (for a time offset between sensors: cam_imu_offset)"),
        Need::Depth => format!("depth corruptions need depth, and {clause}"),
        Need::Lens if setting.lenses == Lenses::Radtan => format!("{}'s calibration files (EuRoC's sensor.yaml, ORB-SLAM3's stereo settings) describe radial-tangential lenses: use distortion:radtan(k1,k2,p1,p2)", setting.input),
        Need::Lens => format!("{} does not support a lens yet; the one-camera render and the EuRoC rigs (radtan) do", setting.input),
        Need::CaptureOrder => format!("{name} carries its state from frame to frame, so its frames must run in capture order from the first, and {clause}: make a dataset of them instead (render or perturb to a folder)"),
        Need::LightLayers => format!("{name} changes the scene's lamps and daylight, which only the built-in scenes keep apart (a mesh's light is baked into its colours), and {clause}"),
        Need::FreeFloor => format!("{name} walks people over the scene's free floor, which only the built-in scenes know, and {clause}"),
        Need::Imu => format!("IMU items need an IMU, and {clause}; render a rig with an IMU (stereo-imu in the EuRoC layout, rgbd-imu in the TUM layout, a rig file with [imu]) or perturb a EuRoC dataset with imu0/"),
    }
}
