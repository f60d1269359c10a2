//! Built-in procedural scenes named like the Replica SLAM sequences: three furnished rooms and five
//! offices, 5–9 m across. Each is a pure function of its name (counter-based hashing, no global
//! RNG): [`layouts`] places the furniture, [`textures`] paints the surfaces, [`lighting`] bakes a
//! view-independent light (shadows, bounces) into the vertex colours and [`trajectory`] draws the default camera path.

mod exposure;
mod furniture;
mod layouts;
mod lighting;
mod mesh_builder;
mod rng;
mod scene_builder;
mod textures;
mod trajectory;

#[cfg(test)]
mod checks;

use glam::Vec2;

use crate::Scene;
use furniture::Style;
use lighting::Lighting;
use scene_builder::SceneBuilder;
use trajectory::Track;

/// Names accepted by `--scene`, in the order Replica lists them.
pub const BUILTIN_SCENES: [&str; 8] = [
    "room0", "room1", "room2", "office0", "office1", "office2", "office3", "office4",
];

/// Poses on the default path of the built-in scene `name` (without building the scene).
pub fn builtin_path_length(name: &str) -> Option<usize> {
    layouts::blueprint(name).map(|_| trajectory::FRAMES)
}

/// The built-in scene of that name, or `None`.
pub fn build(name: &str) -> Option<Scene> {
    let plan = layouts::blueprint(name)?;
    let seed = rng::seed_from_name(name);
    let room = plan.room;
    let lighting = Lighting {
        lamps: plan
            .lamps
            .iter()
            .map(|&(x, y)| Vec2::new(x, y).extend(room.height - 0.3))
            .collect(),
        windows: Vec::new(),
    };
    let mut b = SceneBuilder::new(seed, lighting);
    let style = Style::new(&mut b);
    let finish = (plan.finish)(&mut b, &style);
    room.shell(&mut b, &finish);
    let fixture = furniture::tinted(style.paint, [1.0, 1.0, 0.97]).glowing();
    for &(x, y) in plan.lamps {
        room.ceiling_light(&mut b, &fixture, x, y, plan.panel_lights);
    }
    (plan.furnish)(&mut b, &style, &room);
    let room_half = Vec2::new(room.width, room.depth) / 2.0;
    let track = Track {
        centre: plan.track_centre,
        half: room_half - Vec2::splat(plan.track_margin) - plan.track_centre.abs(),
        room_half,
        height: room.height,
    };
    let trajectory =
        trajectory::default_trajectory(&track, rslam_core::hash::splitmix64(seed ^ 0x7472_616a));
    Some(b.finish(name, trajectory))
}
