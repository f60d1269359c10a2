//! Baked, view-independent lighting of the built-in scenes, like the irradiance a light-map
//! baker stores: ceiling lamps (small discs) and windows (daylight through rectangles) seen
//! through shadow rays, plus the light the room's own surfaces reflect, gathered with rays
//! ([`bake`]). The result is one irradiance per vertex, multiplied into the vertex colours;
//! it is computed once per scene version and kept on disk ([`cache`]).

mod bake;
mod cache;
mod sampling;

pub use bake::{bake, BakeInput};

use glam::Vec3;

/// Light sources of a room, in world coordinates.
#[derive(Clone, Debug, Default)]
pub struct Lighting {
    /// Centres of the lamps' emitting discs (horizontal, radius [`LAMP_RADIUS`]).
    pub lamps: Vec<Vec3>,
    pub windows: Vec<Window>,
}

/// A window pane: `corner` (top left seen from the room), its `right` and `down` edges.
#[derive(Clone, Copy, Debug)]
pub struct Window {
    pub corner: Vec3,
    pub right: Vec3,
    pub down: Vec3,
}

impl Window {
    /// Unit normal into the room.
    pub fn normal(&self) -> Vec3 {
        self.down.cross(self.right).normalize()
    }

    pub fn area(&self) -> f32 {
        self.right.cross(self.down).length()
    }
}

/// Radius of a lamp's emitting disc, metres: soft shadows like a frosted bulb's.
pub const LAMP_RADIUS: f32 = 0.15;
