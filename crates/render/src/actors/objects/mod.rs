//! Things that move through a scene without walking (`objects`): the room's door swings open
//! and shut while the camera can see it ([`door`]), and chairs are pushed across the free floor,
//! one of them to NEAR metres of the camera ([`chair`]). Each is a [`RigidActor`] planned from the
//! seed so that, compared every 5 ms ([`CameraTrack::instants`]) with [`MOTION_MARGIN`] to
//! spare, it never touches the scene, the camera, a walker or another object.

mod chair;
mod door;

use glam::{Vec2, Vec3};
use rslam_core::{Pose, Trajectory};

use super::footprint::segment_distance;
use super::plan::{CameraTrack, CAMERA_CLEARANCE};
use super::WalkerParams;
use super::{FloorMap, RigidActor, Walker};
use crate::scene::builtin::rng::Rng;
use crate::Scene;

/// Metres kept beyond touching at each check: more than anything here moves in a check step
/// (a door's edge at 2 rad/s, a walker hurrying at 2.5 m/s).
const MOTION_MARGIN: f32 = 0.02;
/// Metres kept between two objects, or an object and a walker.
const OBJECT_GAP: f32 = 0.05;
/// Seconds between the poses a motion is sampled at (linear between them).
const POSE_STEP_S: f64 = 0.02;
/// A person carrying a box walks this fast, metres per second.
const CARRYING_SPEED: f32 = 0.9;
/// The nearest a walker's path is planned to the camera, metres (`actors`' least NEAR).
const MIN_WALKER_NEAR: f32 = 0.4;
/// Tries per object before the floor counts as too crowded.
const ATTEMPTS: usize = 300;

/// How many things move, how fast and how near the camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectParams {
    /// Things moved: the door, where the scene has one that has room to swing; from three on, a
    /// box carried by a person; the rest chairs.
    pub count: u32,
    /// A pushed chair's top speed, metres per second.
    pub speed_m_s: f32,
    /// How near the first pushed chair's footprint comes to the camera centre, metres.
    pub near_m: f32,
}

impl ObjectParams {
    /// People carrying a box among the things moved: one from three things on, walking at a
    /// laden pace to within NEAR of the camera (or the nearest a walker may come).
    pub fn box_carriers(&self) -> Option<WalkerParams> {
        (self.count >= 3).then(|| WalkerParams {
            count: 1,
            speed_m_s: CARRYING_SPEED,
            near_m: self.near_m.max(MIN_WALKER_NEAR),
            ahead_m: None,
        })
    }
}

/// What a planned object covers of the floor at an instant: the points within `radius` of the
/// segment `ends`.
#[derive(Clone, Copy, Debug)]
struct Capsule {
    ends: [Vec2; 2],
    radius: f32,
}

impl Capsule {
    fn gap(&self, other: &Capsule) -> f32 {
        segment_distance(self.ends, other.ends) - self.radius - other.radius
    }
}

/// A planned object and how to find its capsule at an instant.
struct Placed {
    actor: RigidActor,
    shape: Shape,
}

#[derive(Clone, Copy, Debug)]
enum Shape {
    /// A footprint circle round the origin.
    Round,
    /// A door leaf from its hinge (the origin) along its frame's x.
    Leaf { width: f32, thickness: f32 },
}

impl Shape {
    /// What `actor` of this shape covers of the floor `t` seconds from the start.
    fn capsule_at(self, actor: &RigidActor, t: f64) -> Capsule {
        let (turn, at) = actor.pose_at(t);
        match self {
            Shape::Round => Capsule {
                ends: [at.truncate(); 2],
                radius: actor.radius,
            },
            Shape::Leaf { width, thickness } => Capsule {
                ends: [at.truncate(), (at + turn * Vec3::X * width).truncate()],
                radius: thickness,
            },
        }
    }
}

/// What a new object keeps clear of: the camera, the walkers and the objects placed before it.
struct Obstacles<'a> {
    camera: &'a CameraTrack,
    walkers: &'a [Walker],
    placed: Vec<Placed>,
}

impl Obstacles<'_> {
    /// Whether `shape` of `actor` keeps clear of everything at every instant, and the nearest
    /// its capsule comes to the camera centre.
    fn clear(&self, actor: &RigidActor, shape: Shape) -> Option<f32> {
        let mut closest = f32::INFINITY;
        for t in self.camera.instants() {
            let own = shape.capsule_at(actor, t);
            let eye = Capsule {
                ends: [self.camera.at(t).truncate(); 2],
                radius: 0.0,
            };
            let to_camera = own.gap(&eye);
            closest = closest.min(to_camera);
            if to_camera < CAMERA_CLEARANCE + MOTION_MARGIN {
                return None;
            }
            let walkers = self.walkers.iter().map(|w| {
                let stride = w.path.at(t);
                Capsule {
                    ends: w.footprint.segment(stride.position, stride.heading),
                    radius: w.footprint.radius,
                }
            });
            let objects = self.placed.iter().map(|p| p.shape.capsule_at(&p.actor, t));
            if walkers
                .chain(objects)
                .any(|other| own.gap(&other) < OBJECT_GAP + MOTION_MARGIN)
            {
                return None;
            }
        }
        Some(closest)
    }
}

/// The objects of `params` in `scene`, clear of the camera on `camera`, of `walkers` and of the
/// user's actors `user`, or why none fit.
pub(super) fn plan(
    scene: &Scene,
    map: &FloorMap,
    params: &ObjectParams,
    seed: u64,
    (camera, walkers, user): (&CameraTrack, &[Walker], &[RigidActor]),
) -> Result<Vec<RigidActor>, String> {
    let rng = Rng::new(seed).fork("objects");
    let users = user.iter().map(|actor| Placed {
        actor: actor.clone(),
        shape: Shape::Round,
    });
    let mut obstacles = Obstacles {
        camera,
        walkers,
        placed: users.collect(),
    };
    let door = (scene.floor.and_then(|f| f.door))
        .and_then(|d| door::plan(scene, &d, &mut rng.fork("door"), &obstacles));
    let carried = usize::from(params.box_carriers().is_some());
    let mut chairs = params.count as usize - carried;
    if let Some(placed) = door {
        obstacles.placed.push(placed);
        chairs -= 1;
    }
    let floor = chair::ChairFloor::of(map, camera, (walkers, user));
    for k in 0..chairs {
        let mut rng = rng.fork(&format!("chair {k}"));
        let near = if k == 0 {
            params.near_m
        } else {
            1.5 * params.near_m + 0.5
        };
        let placed = (0..ATTEMPTS)
            .find_map(|_| {
                let speed_near = (params.speed_m_s, near);
                chair::plan(&floor, &mut rng, speed_near, &obstacles)
            })
            .ok_or_else(|| {
                format!(
                    "chair {} of {chairs}: no way over the free floor keeps clear of the furniture, the camera, the walkers and the other objects in {ATTEMPTS} tries; ask for fewer objects",
                    k + 1
                )
            })?;
        obstacles.placed.push(placed);
    }
    let moved = obstacles.placed.into_iter().skip(user.len());
    Ok(moved.map(|p| p.actor).collect())
}

/// Smoothstep: 0 at 0, 1 at 1, at rest at both ends.
fn ease(u: f64) -> f64 {
    let u = u.clamp(0.0, 1.0);
    u * u * (3.0 - 2.0 * u)
}

/// Poses every [`POSE_STEP_S`] over each `(start, end)` span of `moves` (and at its ends),
/// from `pose(span index, eased progress)`.
fn sampled(moves: &[[f64; 2]], pose: impl Fn(usize, f64) -> Pose) -> Trajectory {
    let (mut times, mut poses) = (Vec::new(), Vec::new());
    for (k, &[start, end]) in moves.iter().enumerate() {
        let steps = ((end - start) / POSE_STEP_S).ceil().max(1.0) as usize;
        for i in 0..=steps {
            let u = i as f64 / steps as f64;
            times.push(start + u * (end - start));
            poses.push(pose(k, ease(u)));
        }
    }
    Trajectory::new(times, poses)
}
