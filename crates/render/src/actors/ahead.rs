//! A walker who keeps in front of the camera all along, as the person the camera follows in
//! Bonn RGB-D's `person_tracking` and the people who stay in view in TUM's `walking_*`: it
//! heads, over the free floor, for the point AHEAD metres in front of where the camera will
//! look a moment later (the free point of the view nearest it), at its walking speed, finding
//! its way again a few times a second. Where the camera looks at no free floor it walks on to
//! where it was heading and waits there. What it costs ORB-SLAM3 against walkers that pass is in
//! docs/src/validity.md ("A walker kept in view").

use glam::Vec2;

use super::floor_map::FloorMap;
use super::plan::{
    clears_the_scene, corners, room_to_turn, within_angle, CameraTrack, Surroundings, Walk,
    CHECK_STEP_S, ROUTE_MARGIN,
};
use super::walk_path::{Route, WalkPath};
use super::{Footprint, RigidActor};

/// Seconds ahead the walker looks at where the camera will look: it gets there as the camera
/// does, rather than trailing it.
const ANTICIPATION_S: f64 = 0.5;
/// Seconds between two times it finds its way.
const REPLAN_S: f64 = 0.2;
/// It heads for a point within this angle of the camera's axis over the floor, radians (inside
/// TUM's view, 31° either side).
const GOAL_HALF_ANGLE: f32 = 0.5;
/// Metres the point it heads for must move before it changes its way: it does not turn at
/// every sway of the camera.
const GOAL_MOVED: f32 = 0.3;
/// Its ways keep this many half-lengths of its footprint clear beyond its width: with its width
/// only, its footprint met the furniture on all 8 draws on room0, office0, office1 and office2
/// (seed 0); with a whole half-length, office1's walker ahead was in view 0.37 of the time
/// instead of 1.00.
const WAY_HALF_LENGTHS: f32 = 0.75;
/// It heads for no point nearer the camera than this share of AHEAD.
const NEAREST_AHEAD: f32 = 0.6;
/// Metres between the points of its route.
const ROUTE_SPACING: f32 = 0.05;

/// The walk of a walker with `footprint` at `speed` m/s keeping `ahead` metres in front of the
/// camera over the floor `map`, clear of the camera and of the user's `rigid` actors at every
/// instant; `None` where the floor in view never has room for it, or where its footprint would
/// meet the scene (stopping where it can turn round as well as anywhere its width passes) or
/// come too near the camera or a rigid actor.
pub(super) fn walker_ahead(
    map: &FloorMap,
    footprint: &Footprint,
    (speed, ahead): (f32, f32),
    camera: &CameraTrack,
    rigid: &[RigidActor],
) -> Option<Walk> {
    let around = Surroundings::new((footprint, speed), camera, (&[], rigid));
    // It heads for no point where its body, turned any way, could reach the camera.
    let least = (around.camera_gap() + footprint.half_length).max(NEAREST_AHEAD * ahead);
    let passage = footprint.radius + WAY_HALF_LENGTHS * footprint.half_length + ROUTE_MARGIN;
    let region = map.largest_region(passage);
    let roomy = room_to_turn(map, &region, footprint);
    let walk_stopping_at = |stops: &[Vec2]| -> Option<Walk> {
        let goal_at = |t: f64| {
            let eye = camera.at(t).truncate();
            let forward = camera.axis_at(t).truncate().normalize_or_zero();
            let wanted = eye + forward * ahead.max(least);
            (stops.iter().copied())
                .filter(|&p| {
                    p.distance(eye) >= least && within_angle((eye, forward), p, GOAL_HALF_ANGLE)
                })
                .min_by(|a, b| a.distance(wanted).total_cmp(&b.distance(wanted)))
        };
        let steps = (camera.duration() / CHECK_STEP_S).ceil() as usize + 1;
        let replan = (REPLAN_S / CHECK_STEP_S).round() as usize;
        // Where it stands at the start: where it first heads for.
        let mut at = (0..steps)
            .step_by(replan)
            .find_map(|i| goal_at(i as f64 * CHECK_STEP_S + ANTICIPATION_S))?;
        let mut goal = at;
        let mut way: Vec<Vec2> = Vec::new();
        let mut positions = Vec::with_capacity(steps);
        for i in 0..steps {
            let t = i as f64 * CHECK_STEP_S;
            if i % replan == 0 {
                let next = goal_at(t + ANTICIPATION_S).filter(|g| g.distance(goal) >= GOAL_MOVED);
                if let Some(found) = next.and_then(|g| map.way(at, g, passage)) {
                    goal = *found.last().expect("a way has its goal");
                    way = corners(map, &found, passage);
                    way.push(goal);
                    way.remove(0);
                }
            }
            let mut left = speed * CHECK_STEP_S as f32;
            while left > 0.0 && !way.is_empty() {
                let d = at.distance(way[0]);
                if d <= left {
                    at = way.remove(0);
                    left -= d;
                } else {
                    at += (way[0] - at) * (left / d);
                    left = 0.0;
                }
            }
            positions.push(at);
        }
        let path = path_through(&positions, speed)?;
        if !clears_the_scene(map, path.route(), footprint) {
            return None;
        }
        let walk = Walk::timed(path, footprint, camera);
        let clear = camera.instants().all(|t| {
            let (p, facing) = walk.path.facing_at(t);
            around.room(footprint.segment_facing(p, facing), t) >= 0.0
        });
        clear.then_some(walk)
    };
    // Stopping anywhere its width passes keeps it in view longest (on office1's narrow ring);
    // where its footprint then meets the scene (coming to a stop face to a wall), it stops only
    // where it can turn round.
    walk_stopping_at(&region).or_else(|| walk_stopping_at(&roomy))
}

/// The walk through `positions` (one every [`CHECK_STEP_S`]) at `speed`: its route the
/// polyline through them [`ROUTE_SPACING`] apart, and its place along it at each step; `None`
/// when it never moves.
fn path_through(positions: &[Vec2], speed: f32) -> Option<WalkPath> {
    let mut points = vec![positions[0]];
    // Metres along the route to its last point.
    let mut length = 0.0;
    let mut along = Vec::with_capacity(positions.len());
    for &p in positions {
        let d = p.distance(points[points.len() - 1]);
        // Between two of the route's points the walker is within millimetres of the straight
        // piece joining them.
        along.push(length + d);
        if d >= ROUTE_SPACING {
            points.push(p);
            length += d;
        }
    }
    (points.len() >= 2).then(|| WalkPath::new(Route::open(&points, 1), speed, CHECK_STEP_S, along))
}
