//! The perturbation panel's state: an editable list of catalogue items (severity or explicit
//! parameters, static or dynamic) and the path and stream items, turned into a spec string that
//! the spec parser of `rslam-perturb` reads, the same string `rslam render --perturb` takes.

use rslam_core::Distortion;
use rslam_perturb::light::LightSpec;
use rslam_perturb::sensor::{distortion, Exposure, RollingShutter};
use rslam_perturb::world::WorldSpec;
use rslam_perturb::{find, Between, Level, PerturbSpec, Severity, CATALOGUE};

/// How one catalogue item is set.
#[derive(Clone, Debug, PartialEq)]
pub enum ItemSetting {
    /// Severity 0..=5, real where the item interpolates; `dynamic`: each frame draws its
    /// severity from [0, severity].
    Severity { severity: Severity, dynamic: bool },
    /// The text of an explicit parameter form, e.g. `0.42-10` for `depth_range`.
    Explicit(String),
}

#[derive(Clone, Debug, PartialEq)]
pub struct EditorItem {
    pub name: &'static str,
    pub setting: ItemSetting,
}

impl EditorItem {
    pub fn new(name: &'static str) -> Self {
        Self {
            name,
            setting: ItemSetting::Severity {
                severity: Severity::whole(3).expect("3 is a severity"),
                dynamic: false,
            },
        }
    }

    /// Whether the item takes real severities (its parameters interpolate between rows).
    pub fn takes_real_severities(&self) -> bool {
        find(self.name).is_some_and(|e| matches!(e.between, Between::Interpolated(_)))
    }

    /// The explicit form's syntax, where the catalogue gives one.
    pub fn explicit_syntax(&self) -> Option<&'static str> {
        find(self.name)
            .and_then(|e| e.explicit.as_ref())
            .map(|f| f.syntax)
    }

    /// The explicit form's example text, to start editing from.
    pub fn explicit_example(&self) -> Option<&'static str> {
        find(self.name)
            .and_then(|e| e.explicit.as_ref())
            .map(|f| f.example)
    }

    /// What the catalogue says the current severity means (e.g. "[0.5, 3.8] m").
    pub fn parameters(&self) -> String {
        match (&self.setting, find(self.name)) {
            (ItemSetting::Severity { severity, .. }, Some(entry)) => {
                match (severity.as_whole(), severity.floor(), severity.ceil()) {
                    (Some(0), ..) => "clean".to_string(),
                    (Some(s), ..) => (entry.parameters)(s),
                    (None, 0, high) => format!("between clean and {}", (entry.parameters)(high)),
                    (None, low, high) => format!(
                        "between {} and {}",
                        (entry.parameters)(low),
                        (entry.parameters)(high)
                    ),
                }
            }
            _ => String::new(),
        }
    }

    fn text(&self) -> String {
        match &self.setting {
            ItemSetting::Severity { severity, dynamic } => {
                let mode = if *dynamic { "@dynamic" } else { "" };
                format!("{}:{severity}{mode}", self.name)
            }
            ItemSetting::Explicit(text) => format!("{}:{}", self.name, text.trim()),
        }
    }
}

/// A trajectory deviation of the panel: sigma, and whether it is temporally smooth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeviationSetting {
    pub sigma: f64,
    pub smooth: bool,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct SpecEditor {
    /// Image and depth corruptions; within each group this is the order applied.
    pub items: Vec<EditorItem>,
    /// `rot:DEGREES` (scenes only).
    pub rotation: Option<DeviationSetting>,
    /// `trans:METRES` (scenes only).
    pub translation: Option<DeviationSetting>,
    /// `fast:K`.
    pub fast: Option<u32>,
    /// `misalign:FRAMES`, and `@dynamic`.
    pub misalign: Option<(u32, bool)>,
    /// `exposure:MS[@K]` (scenes only), kept as given: the panel has no control for it yet.
    pub exposure: Option<Exposure>,
    /// `rolling_shutter:MS` (scenes only), kept as given.
    pub rolling_shutter: Option<RollingShutter>,
    /// `distortion:MODEL(…)` (scenes only), kept as given.
    pub distortion: Option<Distortion>,
    /// `lights`, `flicker`, `daylight` (built-in scenes only).
    pub light: LightSpec,
    /// `actors` (built-in scenes only).
    pub world: WorldSpec,
}

impl SpecEditor {
    /// The editor holding `spec`.
    pub fn from_spec(spec: &PerturbSpec) -> Self {
        let items = spec
            .frame_items()
            .filter_map(|item| {
                let entry = find(&item.name)?;
                let setting = match &item.level {
                    Level::Severity { severity, dynamic } => ItemSetting::Severity {
                        severity: *severity,
                        dynamic: *dynamic,
                    },
                    Level::Explicit { values } => {
                        let form = entry.explicit.as_ref()?;
                        ItemSetting::Explicit((form.format)(values))
                    }
                };
                Some(EditorItem {
                    name: entry.name,
                    setting,
                })
            })
            .collect();
        let deviation = |d: Option<rslam_perturb::Deviation>| {
            d.map(|d| DeviationSetting {
                sigma: d.sigma,
                smooth: d.smooth,
            })
        };
        Self {
            items,
            rotation: deviation(spec.rotation),
            translation: deviation(spec.translation),
            fast: spec.fast,
            misalign: spec.misalign.map(|m| (m.frames, m.dynamic)),
            exposure: spec.exposure,
            rolling_shutter: spec.rolling_shutter,
            distortion: spec.distortion,
            light: spec.light,
            world: spec.world,
        }
    }

    /// Catalogue entries not in the list yet (a spec names each once), in catalogue order.
    pub fn addable(&self) -> impl Iterator<Item = &'static str> + '_ {
        CATALOGUE
            .iter()
            .map(|e| e.name)
            .filter(|name| self.items.iter().all(|i| i.name != *name))
    }

    /// Adds catalogue item `name` at severity 3 (does nothing for an unknown or listed name).
    pub fn add(&mut self, name: &str) {
        let Some(entry) = find(name) else { return };
        if self.items.iter().all(|i| i.name != entry.name) {
            self.items.push(EditorItem::new(entry.name));
        }
    }

    pub fn remove(&mut self, index: usize) {
        if index < self.items.len() {
            self.items.remove(index);
        }
    }

    /// Moves item `index` one place up (`up`) or down.
    pub fn move_item(&mut self, index: usize, up: bool) {
        let other = if up {
            index.checked_sub(1)
        } else {
            Some(index + 1)
        };
        if let Some(other) = other.filter(|&o| o < self.items.len() && index < self.items.len()) {
            self.items.swap(index, other);
        }
    }

    /// The spec as typed by the panel, in the order of the list.
    pub fn text(&self) -> String {
        let mut parts: Vec<String> = Vec::new();
        for (name, deviation) in [("rot", self.rotation), ("trans", self.translation)] {
            if let Some(d) = deviation {
                let mode = if d.smooth { "@smooth" } else { "" };
                parts.push(format!("{name}:{}{mode}", d.sigma));
            }
        }
        parts.extend(self.exposure.map(|e| e.to_string()));
        parts.extend(self.rolling_shutter.map(|r| r.to_string()));
        parts.extend(self.distortion.as_ref().map(distortion::item));
        parts.extend(self.light.items());
        parts.extend(self.world.items());
        parts.extend(self.items.iter().map(EditorItem::text));
        if let Some(k) = self.fast {
            parts.push(format!("fast:{k}"));
        }
        if let Some((frames, dynamic)) = self.misalign {
            let mode = if dynamic { "@dynamic" } else { "" };
            parts.push(format!("misalign:{frames}{mode}"));
        }
        parts.join(",")
    }

    /// The spec the panel describes, parsed by the spec parser (empty: nothing perturbed).
    pub fn spec(&self) -> Result<PerturbSpec, rslam_perturb::PerturbError> {
        match self.text() {
            text if text.is_empty() => Ok(PerturbSpec::default()),
            text => PerturbSpec::parse(&text),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_spec_round_trips_through_the_editor() {
        let text = "rot:0.5@smooth,exposure:20@8,rolling_shutter:30,distortion:radtan(-0.28,0.07,0.0002,0.00002),lights:3,flicker:100/0.5,daylight:0.4/10,actors:2/1.2/0.8,fog:4,gaussian_noise:2@dynamic,depth_range:0.42-10,fast:2,misalign:3@dynamic";
        let spec = PerturbSpec::parse(text).unwrap();
        let editor = SpecEditor::from_spec(&spec);
        assert_eq!(editor.spec().unwrap(), spec);
        assert_eq!(editor.text(), text);
    }

    #[test]
    fn add_move_remove() {
        let mut editor = SpecEditor::default();
        assert_eq!(editor.spec().unwrap(), PerturbSpec::default());
        editor.add("fog");
        editor.add("gaussian_noise");
        editor.add("fog");
        editor.add("no_such_thing");
        assert_eq!(editor.text(), "fog:3,gaussian_noise:3");
        editor.move_item(1, true);
        assert_eq!(editor.text(), "gaussian_noise:3,fog:3");
        editor.move_item(1, false);
        assert_eq!(
            editor.text(),
            "gaussian_noise:3,fog:3",
            "last item stays last"
        );
        editor.remove(0);
        assert_eq!(editor.text(), "fog:3");
        assert!(!editor.addable().any(|n| n == "fog"));
    }

    #[test]
    fn a_bad_explicit_value_is_a_spec_error_naming_the_item() {
        let mut editor = SpecEditor::default();
        editor.add("depth_range");
        editor.items[0].setting = ItemSetting::Explicit("10-1".into());
        let e = editor.spec().unwrap_err().to_string();
        assert!(e.contains("depth_range:10-1"), "{e}");
    }
}
