//! One blueprint per built-in scene: the room, its lights, its surface finish and the furniture.
//! Everything taller than ~0.9 m stands within ~0.7 m of a wall, so the camera track (the room
//! less `track_margin` on every side) stays clear of it.

mod offices;
mod rooms;

use glam::Vec2;

use super::furniture::architecture::{Finish, Room};
use super::furniture::Style;
use super::scene_builder::SceneBuilder;

pub struct Blueprint {
    pub room: Room,
    /// Ceiling lights (x, y).
    pub lamps: &'static [(f32, f32)],
    pub panel_lights: bool,
    pub track_centre: Vec2,
    pub track_margin: f32,
    pub finish: fn(&mut SceneBuilder, &Style) -> Finish,
    pub furnish: fn(&mut SceneBuilder, &Style, &Room),
}

pub fn blueprint(name: &str) -> Option<Blueprint> {
    Some(match name {
        "room0" => rooms::room0(),
        "room1" => rooms::room1(),
        "room2" => rooms::room2(),
        "office0" => offices::office0(),
        "office1" => offices::office1(),
        "office2" => offices::office2(),
        "office3" => offices::office3(),
        "office4" => offices::office4(),
        _ => return None,
    })
}
