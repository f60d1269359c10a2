//! Light that changes during a sequence (docs/src/perturbations.md, "Light"): lamps switched off
//! and on ([`switching`]), mains flicker ([`flicker`]) and daylight drifting ([`daylight`]). They
//! act on the light itself, not on a finished image: a built-in scene keeps each lamp's and the
//! daylight's share of its colours as a layer, and every render mixes the layers with the light
//! state of the interval it exposes ([`LightSchedule::weights`]), so shading, shadows and the
//! balance between lamps and windows change as in a real room, and an `auto_exposure` after
//! them follows the light with its lag.

pub mod daylight;
pub mod flicker;
mod schedule;
pub mod switching;

pub use daylight::Daylight;
pub use flicker::Flicker;
pub use schedule::{LayerKind, LightSchedule};
pub use switching::Switching;

use serde::{Deserialize, Serialize};

use crate::applies::{ItemEntry, Need};

pub static LIGHT_ITEMS: &[ItemEntry] = &[
    ItemEntry {
        name: switching::NAME,
        syntax: "lights:1-5 | lights:FRACTION/EVERY/DARK",
        description: "lamps switched off and back on at seeded times: events come every EVERY s on average (Poisson), each turns off FRACTION of the lamps (at least one) for DARK s; the daylight stays; severities 1-5 = 0.25/20/2, 0.25/10/3, 0.5/8/4, 0.75/6/5, 1/5/6",
        needs: &[Need::Scene, Need::LightLayers],
    },
    ItemEntry {
        name: flicker::NAME,
        syntax: "flicker:HZ | flicker:HZ/DEPTH",
        description: "the lamps' intensity 1 + DEPTH·sin(2π·HZ·t + φ) (HZ 100 or 120 for 50 or 60 Hz mains; DEPTH 0.3 by default, a fluorescent tube on a magnetic ballast), sampled at each frame's instant or, with exposure, integrated over the exposure (and per band of rows under rolling_shutter), so it beats against the frame rate",
        needs: &[Need::Scene, Need::LightLayers],
    },
    ItemEntry {
        name: daylight::NAME,
        syntax: "daylight:1-5 | daylight:DIM/PERIOD",
        description: "window light drifting like passing clouds: its intensity falls by up to DIM (a smooth seeded curve with a new level every PERIOD s), bluer as it dims; severities 1-5 = 0.2/30, 0.35/20, 0.5/12, 0.7/8, 0.9/5",
        needs: &[Need::Scene, Need::LightLayers],
    },
];

/// The light items of a spec.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LightSpec {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lights: Option<Switching>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flicker: Option<Flicker>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub daylight: Option<Daylight>,
}

/// Whether `name` is a light item.
pub fn is_light_item(name: &str) -> bool {
    LIGHT_ITEMS.iter().any(|e| e.name == name)
}

impl LightSpec {
    /// Takes the light item `name` with its value; the error says what was expected.
    pub fn add(&mut self, name: &str, value: &str, mode: Option<&str>) -> Result<(), String> {
        if let Some(m) = mode {
            return Err(format!("{name} takes no mode, got '@{m}'"));
        }
        match name {
            switching::NAME => self.lights = Some(Switching::parse(value)?),
            flicker::NAME => self.flicker = Some(Flicker::parse(value)?),
            _ => self.daylight = Some(Daylight::parse(value)?),
        }
        Ok(())
    }

    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }

    /// The items as written canonically.
    pub fn items(&self) -> Vec<String> {
        [
            self.lights.map(|s| s.to_string()),
            self.flicker.map(|f| f.to_string()),
            self.daylight.map(|d| d.to_string()),
        ]
        .into_iter()
        .flatten()
        .collect()
    }
}

/// A severity 1..=5 or `None` when `value` is not one.
fn severity(value: &str) -> Option<u8> {
    crate::spec::parse_severity(value)
}

/// `A/B/…` as `count` finite numbers each passing `valid`, or the message naming `example`.
fn numbers(
    value: &str,
    count: usize,
    valid: impl Fn(usize, f64) -> bool,
    expected: &str,
) -> Result<Vec<f64>, String> {
    let parsed: Option<Vec<f64>> = value
        .split('/')
        .map(|v| v.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect();
    parsed
        .filter(|v| v.len() == count && v.iter().enumerate().all(|(i, &x)| valid(i, x)))
        .ok_or_else(|| format!("'{value}': expected {expected}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_descriptions_state_the_severity_tables() {
        let description = |name: &str| {
            LIGHT_ITEMS
                .iter()
                .find(|e| e.name == name)
                .unwrap()
                .description
        };
        let lights = format!("severities 1-5 = {}", Switching::severities());
        assert!(description(switching::NAME).contains(&lights), "{lights}");
        let daylight = format!("severities 1-5 = {}", Daylight::severities());
        assert!(
            description(daylight::NAME).contains(&daylight),
            "{daylight}"
        );
    }
}
