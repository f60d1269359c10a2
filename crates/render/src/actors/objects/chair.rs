//! A chair pushed across the room: it stands from the start where the camera never comes, is
//! pushed at an instant past a point NEAR metres from the camera and on to another such place
//! (the shortest ways over the free floor, an open Catmull–Rom spline through their corners),
//! speeding up and slowing down, turning a little as it goes, and stays there.

use std::f32::consts::TAU;

use glam::{DQuat, DVec3, Vec2, Vec3};
use rslam_core::Pose;

use super::{sampled, Obstacles, Placed, Shape, MOTION_MARGIN};
use crate::actors::plan::{corners, passing_point, CameraTrack, CAMERA_CLEARANCE};
use crate::actors::walker::hexahedron;
use crate::actors::{FloorMap, MovedObject, RigidActor, RigidLight, Route, Walker};
use crate::scene::builtin::rng::Rng;
use crate::{Mesh, Vertex};

/// Frame and seat colours (sRGB): light wood, dark wood, black, white, red and blue paint.
const PAINTS: [[u8; 3]; 6] = [
    [196, 160, 112],
    [104, 72, 48],
    [40, 40, 44],
    [228, 226, 218],
    [150, 44, 36],
    [52, 88, 140],
];
/// Metres from where it stands to the point near the camera, and on, as the crow flies.
const DISTANCE: (f32, f32) = (1.0, 3.5);
/// Half the seat's width and depth, and the legs' thickness, metres.
const HALF_SEAT: (f32, f32) = (0.21, 0.2);
const LEG: f32 = 0.035;
/// Metres more than the camera clearance a standing chair keeps from every place the camera
/// passes.
const PARKING_GAP: f32 = 0.1;
/// Radians it turns on the way, at most either way.
const TURN: f32 = 0.6;
/// Spline samples per corner-to-corner span.
const SAMPLES_PER_SPAN: usize = 16;
/// Seconds from the start before anything is pushed.
const FIRST_PUSH_S: f64 = 0.5;

/// The radius round a chair's origin that holds it.
fn radius() -> f32 {
    HALF_SEAT.0.hypot(HALF_SEAT.1)
}

/// The floor as chairs see it: where one fits, and where one can stand all through (cells that
/// neither the camera, a walker's route nor a user's actor ever comes near).
pub(super) struct ChairFloor<'a> {
    map: &'a FloorMap,
    free: Vec<Vec2>,
    parking: Vec<Vec2>,
}

impl<'a> ChairFloor<'a> {
    pub(super) fn of(
        map: &'a FloorMap,
        camera: &CameraTrack,
        (walkers, user): (&[Walker], &[RigidActor]),
    ) -> Self {
        let keep = radius() + CAMERA_CLEARANCE + PARKING_GAP;
        let users: Vec<(Vec2, f32)> = (user.iter())
            .flat_map(|a| {
                let reach = radius() + a.radius + PARKING_GAP;
                (camera.times.iter()).map(move |&t| (a.pose_at(t).1.truncate(), reach))
            })
            .collect();
        let off_routes = |p: &Vec2| {
            walkers.iter().all(|w| {
                let reach = radius() + w.footprint.radius + w.footprint.half_length + PARKING_GAP;
                (w.path.route().points().iter()).all(|q| q.distance(*p) >= reach)
            })
        };
        let free = map.free_cells(radius() + MOTION_MARGIN);
        let parking = (free.iter().copied())
            .filter(|p| (camera.positions.iter()).all(|c| c.truncate().distance(*p) >= keep))
            .filter(off_routes)
            .filter(|p| users.iter().all(|(q, reach)| q.distance(*p) >= *reach))
            .collect();
        Self { map, free, parking }
    }
}

/// One try at a chair pushed past `near` metres of the camera (or as near as the floor has room
/// for) at `speed` (top, metres per second), between two places it can stand; `None` when this
/// draw does not fit.
pub(super) fn plan(
    floor: &ChairFloor,
    rng: &mut Rng,
    (speed, near): (f32, f32),
    obstacles: &Obstacles,
) -> Option<Placed> {
    let (map, parking) = (floor.map, &floor.parking);
    let camera = obstacles.camera;
    let mesh = chair(rng);
    let radius = radius();
    let roomy = radius + MOTION_MARGIN;
    let meet = f64::from(rng.range(0.15, 0.85)) * camera.duration();
    let eye = camera.at(meet).truncate();
    let forward = camera.axis_at(meet).truncate().normalize_or_zero();
    let passing = passing_point(rng, &floor.free, (eye, Some(forward)), near + radius)?;
    let mut stands = || {
        let far: Vec<Vec2> = (parking.iter())
            .filter(|p| (DISTANCE.0..DISTANCE.1).contains(&p.distance(passing)))
            .copied()
            .collect();
        (!far.is_empty()).then(|| far[rng.int(0, far.len() as i64) as usize])
    };
    let (start, end) = (stands()?, stands()?);
    let mut through = vec![start];
    for (from, to) in [(start, passing), (passing, end)] {
        let way = map.way(from, to, roomy)?;
        through.extend(corners(map, &way, roomy).into_iter().skip(1));
        through.push(to);
    }
    let route = Route::open(&through, SAMPLES_PER_SPAN);
    if route.points().iter().any(|&p| map.clearance(p) < roomy) {
        return None;
    }
    let length = route.length();
    // `passing` is a waypoint, so a sample of the route.
    let passing_at = route.arc_length_to(passing);
    let push_s = 1.5 * f64::from(length / speed);
    let from = (meet - push_s * unease(f64::from(passing_at / length))).max(FIRST_PUSH_S);
    if from + push_s > camera.duration() {
        return None;
    }
    let (yaw, turn) = (rng.range(0.0, TAU), rng.range(-TURN, TURN));
    let moves = vec![[from, from + push_s]];
    let path = sampled(&moves, |_, eased| {
        let (at, _) = route.at(eased as f32 * length);
        Pose::new(
            DQuat::from_rotation_z(f64::from(yaw + turn * eased as f32)),
            DVec3::new(f64::from(at.x), f64::from(at.y), 0.0),
        )
    });
    let object = MovedObject {
        kind: "chair",
        moves,
        closest_m: 0.0,
    };
    let mut actor = RigidActor::object(object, (mesh, RigidLight::Probe, usize::MAX), path);
    let closest = obstacles.clear(&actor, Shape::Round)?;
    actor.set_closest(closest);
    Some(Placed {
        actor,
        shape: Shape::Round,
    })
}

/// The share of the time at which [`super::ease`] reaches `share` of the way.
fn unease(share: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if super::ease(mid) < share {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// A four-legged chair with a backrest, its origin under the seat's centre, the back towards −x;
/// painted from [`PAINTS`].
fn chair(rng: &mut Rng) -> Mesh {
    let pick = |rng: &mut Rng| {
        let [r, g, b] = PAINTS[rng.int(0, PAINTS.len() as i64) as usize];
        [r, g, b, 255]
    };
    let (frame, seat) = (pick(rng), pick(rng));
    let ((hx, hy), leg) = (HALF_SEAT, LEG);
    let mut mesh = Mesh::default();
    cuboid(&mut mesh, [-hx, -hy, 0.43], [hx, hy, 0.47], seat);
    for (x, y) in [
        (-hx, -hy),
        (-hx, hy - leg),
        (hx - leg, -hy),
        (hx - leg, hy - leg),
    ] {
        let top = if x < 0.0 { 0.88 } else { 0.43 };
        cuboid(&mut mesh, [x, y, 0.0], [x + leg, y + leg, top], frame);
    }
    cuboid(
        &mut mesh,
        [-hx, -hy + leg, 0.62],
        [-hx + 0.02, hy - leg, 0.84],
        seat,
    );
    mesh
}

/// An axis-aligned box of one colour, each face flat.
fn cuboid(mesh: &mut Mesh, min: [f32; 3], max: [f32; 3], color: [u8; 4]) {
    let (lo, hi) = (Vec3::from(min), Vec3::from(max));
    let pick = |bit: bool, a: f32, b: f32| if bit { b } else { a };
    let corners = std::array::from_fn(|i| {
        Vec3::new(
            pick(i & 1 != 0, lo.x, hi.x),
            pick(i & 2 != 0, lo.y, hi.y),
            pick(i & 4 != 0, lo.z, hi.z),
        )
    });
    let surface = hexahedron(corners);
    let first = mesh.vertices.len() as u32;
    let faces = surface.positions.iter().zip(&surface.uvs);
    mesh.vertices.extend(faces.map(|(p, uv)| Vertex {
        position: p.to_array(),
        uv: uv.to_array(),
        color,
        layer: 0,
    }));
    (mesh.indices).extend(surface.indices.iter().map(|i| first + i));
}
