//! Baked, view-independent lighting of the built-in scenes, like the irradiance a light-map
//! baker stores: ceiling lamps (small discs) and windows (daylight through rectangles) seen
//! through shadow rays, plus the light the room's own surfaces reflect, gathered with rays
//! ([`bake`]). The result is one irradiance per vertex, multiplied into the vertex colours;
//! it is computed once per scene version and kept on disk ([`cache`]), with each light's share
//! as a layer of its own for the light items.

mod bake;
mod cache;
mod sampling;

pub use bake::{bake, BakeInput, Baked};

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

impl Lighting {
    /// Layers of a bake: one per lamp, and one for the daylight of all windows if there are any.
    pub fn layer_count(&self) -> usize {
        self.lamps.len() + usize::from(!self.windows.is_empty())
    }
}

/// The layer whose light a glowing vertex at `position` shows: the daylight's when it lies on a
/// window pane (the view outside), else the nearest lamp's (its fixture).
pub fn glowing_layer(lighting: &Lighting, position: [f32; 3]) -> usize {
    let p = Vec3::from(position);
    if lighting.windows.iter().any(|w| w.holds(p)) {
        return lighting.lamps.len();
    }
    let nearest = (lighting.lamps.iter().enumerate())
        .min_by(|a, b| (*a.1 - p).length().total_cmp(&(*b.1 - p).length()));
    nearest.map_or(lighting.lamps.len(), |(l, _)| l)
}

impl Window {
    /// Whether `p` lies on the pane (within 2 cm of its plane).
    fn holds(&self, p: Vec3) -> bool {
        let d = p - self.corner;
        let along = |edge: Vec3| d.dot(edge) / edge.length_squared();
        let (s, t) = (along(self.right), along(self.down));
        let margin = 0.02;
        d.dot(self.normal()).abs() < margin
            && (-0.01..=1.01).contains(&s)
            && (-0.01..=1.01).contains(&t)
    }

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
