//! Items that change the world a scene's camera films, not the camera or its frames
//! (docs/src/perturbations.md, "A world that moves"): people walking through the scene and
//! things moved through it ([`movers`]). A job draws them into every render at the render's
//! instant, so every sensor, shutter and lens sees them where they are.

pub mod movers;

use serde::{Deserialize, Serialize};

pub use movers::{MoverKind, MovingObjects, ObjectKind, WalkerKind, Walkers};

use crate::applies::{ItemEntry, Need};

pub static WORLD_ITEMS: &[ItemEntry] = &[
    ItemEntry {
        name: WalkerKind::NAME,
        syntax: "actors:1-5 | actors:COUNT/SPEED/NEAR[/AHEAD]",
        description: "people walking through the scene: COUNT articulated walkers at SPEED m/s on curved paths over the free floor that keep clear of the furniture, each other and the camera, entering and leaving the view and passing within NEAR m of the camera (or as near as the floor has room for; the manifest has each walker's closest approach); with AHEAD, one of them instead walks in front of the camera all along, heading for the floor AHEAD m in front of where it looks, or as near as the floor has room for (as the person a camera follows in Bonn person_tracking); severities 1-5 = 1/1.2/1, 2/1.2/1, 3/1.2/1, 2/1.2/0.8/2, 3/1.2/0.8/2 (each severity's walkers those below and one more, in the same draw, like TUM fr2 desk_with_person, fr3 walking_*, Bonn crowd; then one of them kept in view, like Bonn person_tracking)",
        needs: &[Need::Scene, Need::FreeFloor],
    },
    ItemEntry {
        name: ObjectKind::NAME,
        syntax: "objects:1-5 | objects:COUNT/SPEED/NEAR",
        description: "things moved through the scene: COUNT objects, first the room's door swinging open while the camera sees it and shutting again (as wide as the furniture lets it), from three on a box carried past the camera by a person, the rest chairs pushed over the free floor at up to SPEED m/s, the first to within NEAR m of the camera; nothing touches the scene, the camera, a walker or another object at any instant; severities 1-5 = 1/0.4/2.5, 2/0.5/2, 2/0.6/1.2, 3/0.7/0.8, 4/0.9/0.5 (like Bonn placing_nonobstructing_box, moving_nonobstructing_box, moving_obstructing_box, moving_obstructing_box2, and beyond)",
        needs: &[Need::Scene, Need::FreeFloor],
    },
];

/// The world items of a spec.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct WorldSpec {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub actors: Option<Walkers>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub objects: Option<MovingObjects>,
}

/// Whether `name` is a world item.
pub fn is_world_item(name: &str) -> bool {
    WORLD_ITEMS.iter().any(|e| e.name == name)
}

impl WorldSpec {
    /// Takes the world item `name` with its value; the error says what was expected.
    pub fn add(&mut self, name: &str, value: &str, mode: Option<&str>) -> Result<(), String> {
        if let Some(m) = mode {
            return Err(format!("{name} takes no mode, got '@{m}'"));
        }
        if name == ObjectKind::NAME {
            self.objects = Some(MovingObjects::parse(value)?);
        } else {
            self.actors = Some(Walkers::parse(value)?);
        }
        Ok(())
    }

    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }

    /// The items as written canonically.
    pub fn items(&self) -> Vec<String> {
        let walkers = self.actors.iter().map(|w| w.to_string());
        walkers
            .chain(self.objects.iter().map(|o| o.to_string()))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_description_states_the_severity_table() {
        let table = format!("severities 1-5 = {}", Walkers::severities());
        assert!(WORLD_ITEMS[0].description.contains(&table), "{table}");
        let table = format!("severities 1-5 = {}", MovingObjects::severities());
        assert!(WORLD_ITEMS[1].description.contains(&table), "{table}");
    }
}
