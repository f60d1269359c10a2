//! The room's door swinging open and shut: its leaf and handle, lit as the scene baked them,
//! turn about the hinge into the room at an instant the camera looks at the door, stay open a
//! while and close; behind them the doorway is a dark opening. The leaf opens as wide as the
//! furniture lets it (sampled from the scene's triangles), and not at all when that is too little.

use glam::{DQuat, Vec2, Vec3};
use rslam_core::Pose;

use super::{sampled, Obstacles, Placed, Shape};
use crate::actors::plan::in_view;
use crate::actors::{MovedObject, RigidActor, RigidLight};
use crate::scene::srgb::linear_to_srgb;
use crate::{Door, Mesh, Scene, Vertex};

/// The widest a door opens, radians (95°), and the least that counts as swinging (35°).
const WIDEST: f32 = 1.66;
const NARROWEST: f32 = 0.61;
/// A door's mean turning speed as it swings, radians per second.
const SWING_RATE: f32 = 1.0;
/// Seconds it stays open.
const HOLD_S: (f32, f32) = (1.5, 4.0);
/// Metres the leaf keeps from furniture as it swings: the handle's depth and a gap.
const SWEEP_GAP: f32 = 0.11;
/// How far the handle stands out from the leaf's room side, metres.
const HANDLE_DEPTH: f32 = 0.06;
/// Things lower than this pass under the leaf (the floor, a rug), metres.
const FLOOR_GAP: f32 = 0.015;
/// Metres between the points a triangle is sampled at for the sweep.
const SAMPLE_SPACING: f32 = 0.02;
/// The opening's light as a share of the leaf's: a dark corridor beyond.
const OPENING_SHADE: f32 = 0.08;
/// Timings tried before the door stays shut.
const TRIES: usize = 60;

/// The door swinging at an instant the camera sees it, clear of everything; `None` when it has
/// no room to swing or no timing keeps it clear.
pub(super) fn plan(
    scene: &Scene,
    door: &Door,
    rng: &mut crate::scene::builtin::rng::Rng,
    obstacles: &Obstacles,
) -> Option<Placed> {
    let widest = sweep_limit(scene, door).min(WIDEST);
    if widest < NARROWEST {
        return None;
    }
    let parts = leaf_and_opening(scene, door)?;
    let camera = obstacles.camera;
    let (along, into) = (Vec2::from(door.along), Vec2::from(door.into_room));
    let side = along.perp_dot(into).signum() as f64;
    let yaw = f64::from(along.to_angle());
    let hinge = Vec3::from(door.hinge).as_dvec3();
    let centre = Vec3::from(door.hinge).truncate() + along * door.width / 2.0;
    let seen: Vec<f64> = (0..camera.times.len())
        .filter(|&k| in_view(camera.positions[k], camera.axes[k], centre))
        .map(|k| camera.times[k])
        .collect();
    let duration = camera.duration();
    let shape = Shape::Leaf {
        width: door.width,
        thickness: door.thickness.max(HANDLE_DEPTH),
    };
    for _ in 0..TRIES {
        let angle = f64::from(rng.range(NARROWEST.max(0.7 * widest), widest));
        let swing_s = 1.5 * angle / f64::from(SWING_RATE);
        let open_at = match seen.len() {
            0 => f64::from(rng.range(0.1, 0.6)) * duration,
            n => (seen[rng.int(0, n as i64) as usize] - swing_s / 2.0).max(0.0),
        };
        let shut_at = open_at + swing_s + f64::from(rng.range(HOLD_S.0, HOLD_S.1));
        let moves = vec![[open_at, open_at + swing_s], [shut_at, shut_at + swing_s]];
        let path = sampled(&moves, |k, eased| {
            let open = if k == 0 { eased } else { 1.0 - eased };
            Pose::new(DQuat::from_rotation_z(yaw + side * open * angle), hinge)
        });
        let object = MovedObject {
            kind: "door",
            moves,
            closest_m: 0.0,
        };
        let mut actor = RigidActor::object(object, parts.clone(), path);
        if let Some(closest) = obstacles.clear(&actor, shape) {
            actor.set_closest(closest);
            return Some(Placed { actor, shape });
        }
    }
    None
}

/// How far the leaf can turn into the room before it comes within [`SWEEP_GAP`] of something
/// of the scene that is not the door, its wall or lower than [`FLOOR_GAP`], radians.
fn sweep_limit(scene: &Scene, door: &Door) -> f32 {
    let (hinge, along, into) = (
        Vec3::from(door.hinge).truncate(),
        Vec2::from(door.along),
        Vec2::from(door.into_room),
    );
    let reach = door.width + SWEEP_GAP;
    let heights = FLOOR_GAP..=door.height + FLOOR_GAP;
    let vertices = &scene.mesh.vertices;
    let near_the_door = (scene.mesh.indices.chunks_exact(3).enumerate())
        .filter(|&(t, _)| !door.owns(3 * t))
        .map(|(_, corners)| [0, 1, 2].map(|i| Vec3::from(vertices[corners[i] as usize].position)))
        .filter(|&[a, b, c]| {
            let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
            hi.z >= *heights.start()
                && lo.z <= *heights.end()
                && (lo.truncate() - hinge).max_element() <= reach
                && (hinge - hi.truncate()).max_element() <= reach
        });
    let mut widest = std::f32::consts::PI;
    for p in near_the_door.flat_map(surface_points) {
        let rel = p.truncate() - hinge;
        let (x, y) = (rel.dot(along), rel.dot(into));
        let r = x.hypot(y);
        if y > 0.001 && heights.contains(&p.z) && r <= reach {
            widest = widest.min(y.atan2(x) - SWEEP_GAP.atan2(r));
        }
    }
    widest
}

/// Points over the triangle `[a, b, c]` no farther apart along its edges than
/// [`SAMPLE_SPACING`].
fn surface_points([a, b, c]: [Vec3; 3]) -> impl Iterator<Item = Vec3> {
    let longest = a.distance(b).max(b.distance(c)).max(c.distance(a));
    let n = ((longest / SAMPLE_SPACING).ceil() as usize).max(1);
    (0..=n).flat_map(move |i| {
        (0..=n - i).map(move |j| {
            let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
            a + (b - a) * u + (c - a) * v
        })
    })
}

/// The leaf and handle as the scene has them, in the door's frame (origin at the hinge, x along
/// the wall to the free edge, z up), lit as baked; then the dark opening behind them, which
/// stays; `None` for a scene without light layers.
fn leaf_and_opening(scene: &Scene, door: &Door) -> Option<(Mesh, RigidLight, usize)> {
    let lights = scene.lights.as_ref()?;
    let layers = lights.kinds.len();
    let (along, into) = (Vec2::from(door.along), Vec2::from(door.into_room));
    let side = along.perp_dot(into).signum();
    let hinge = Vec3::from(door.hinge);
    let to_local = glam::Quat::from_rotation_z(-along.to_angle());
    let mut mesh = Mesh::default();
    let mut light = Vec::new();
    let mut local_index = std::collections::HashMap::new();
    for &(start, end) in &door.indices {
        for &i in &scene.mesh.indices[start as usize..end as usize] {
            let next = local_index.len() as u32;
            let local = *local_index.entry(i).or_insert_with(|| {
                let v = scene.mesh.vertices[i as usize];
                mesh.vertices.push(Vertex {
                    position: (to_local * (Vec3::from(v.position) - hinge)).into(),
                    ..v
                });
                let at = i as usize * layers;
                light.extend_from_slice(&lights.colours[at..at + layers]);
                next
            });
            mesh.indices.push(local);
        }
    }
    let still_from = mesh.vertices.len();
    let mean: Vec<Vec3> = (0..layers)
        .map(|l| {
            let sum: Vec3 = (0..still_from)
                .map(|v| Vec3::from(light[v * layers + l]))
                .sum();
            sum / still_from.max(1) as f32 * OPENING_SHADE
        })
        .collect();
    let total: Vec3 = mean.iter().sum();
    let [r, g, b] = total.to_array().map(linear_to_srgb);
    // 1 mm in front of the wall, behind where the leaf stood.
    let y = side * (-door.thickness + 0.001);
    for (x, z) in [
        (0.0, 0.0),
        (door.width, 0.0),
        (door.width, door.height),
        (0.0, door.height),
    ] {
        mesh.vertices.push(Vertex {
            position: [x, y, z],
            uv: [0.0; 2],
            color: [r, g, b, 255],
            layer: 0,
        });
        light.extend(mean.iter().map(|m| m.to_array()));
    }
    let first = still_from as u32;
    mesh.indices.extend([0, 1, 2, 0, 2, 3].map(|k| first + k));
    Some((mesh, RigidLight::Baked(light), still_from))
}
