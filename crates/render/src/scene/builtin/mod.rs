//! Built-in procedural scenes named like the Replica SLAM sequences: three furnished rooms and five
//! offices, 5–9 m across. Each is a pure function of its name (counter-based hashing, no global
//! RNG): [`layouts`] places the furniture, [`textures`] paints the surfaces, [`lighting`] bakes a
//! view-independent light (shadows, bounces) into the vertex colours and [`trajectory`] draws the default camera path.

mod cache_root;
mod exposure;
mod furniture;
mod layouts;
mod lighting;
mod mesh_builder;
pub(crate) mod rng;
mod scene_builder;
mod textures;
mod trajectory;

#[cfg(test)]
mod checks;

use glam::Vec2;
use rslam_core::Trajectory;

use crate::{FreeFloor, Scene};
use cache_root::cache_root;
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

/// The path of agent `agent` of a multi-agent sequence in the built-in scene `name` (without
/// building the scene): a walk round the same free track as the default path, drawn with a seed of
/// its own and started a golden-ratio share of a lap further round than the agent before, so
/// agents spread round the track, go round in either direction and look at different things.
/// Agent 0's path is the scene's default one. `None` for an unknown name.
pub fn agent_trajectory(name: &str, agent: usize) -> Option<Trajectory> {
    let plan = layouts::blueprint(name)?;
    let golden_ratio_conjugate = 0.618_034_f32;
    Some(trajectory::default_trajectory(
        &track(&plan),
        path_seed(rng::seed_from_name(name), agent),
        (agent as f32 * golden_ratio_conjugate).fract(),
    ))
}

/// Agent 0's seed is the default path's; every further agent steps by the golden-ratio
/// increment before mixing, so agents' draws share nothing.
fn path_seed(scene_seed: u64, agent: usize) -> u64 {
    let base = scene_seed ^ 0x7472_616a;
    rslam_core::hash::splitmix64(
        base.wrapping_add((agent as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15)),
    )
}

/// The free floor area of a blueprint's room that paths may roam.
fn track(plan: &layouts::Blueprint) -> Track {
    let room = plan.room;
    let room_half = Vec2::new(room.width, room.depth) / 2.0;
    Track {
        centre: plan.track_centre,
        half: room_half - Vec2::splat(plan.track_margin) - plan.track_centre.abs(),
        room_half,
        height: room.height,
    }
}

/// Patterned tops among what people walking through a scene wear: this many of each of
/// stripes, checks and printed T-shirts ...
const PATTERNED_TOPS_EACH: usize = 4;
/// ... at these indices of [`clothing_textures`].
pub(crate) const PATTERNED_TOPS: std::ops::Range<usize> = 3..3 + 3 * PATTERNED_TOPS_EACH;

/// What people walking through a scene wear, painted or read from the texture cache like a
/// scene's textures: a plain top and trousers (the upholstery family's fabrics) and shoes (its
/// leather), then the patterned tops ([`PATTERNED_TOPS`]).
pub(crate) fn clothing_textures() -> Vec<crate::Texture> {
    use textures::{Pattern, TextureSpec};
    let plain = [
        (Pattern::Fabric, 0x70),
        (Pattern::Fabric, 0x7a),
        (Pattern::Leather, 0x5e),
    ];
    let patterned = (0..PATTERNED_TOPS_EACH as u64).flat_map(|k| {
        [Pattern::Stripes, Pattern::Checks, Pattern::GarmentPrint].map(|p| (p, 0x90 + k))
    });
    (plain.into_iter().chain(patterned))
        .map(|(pattern, seed)| textures::cache::texture(&TextureSpec { pattern, seed }))
        .collect()
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
    let track = track(&plan);
    let trajectory = trajectory::default_trajectory(&track, path_seed(seed, 0), 0.0);
    let door = b.doors.first().copied();
    let mut scene = b.finish(name, trajectory);
    scene.floor = Some(FreeFloor {
        room_half: track.room_half.into(),
        free_centre: track.centre.into(),
        free_half: track.half.into(),
        ceiling: track.height,
        door,
    });
    Some(scene)
}
