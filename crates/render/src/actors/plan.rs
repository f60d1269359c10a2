//! Planning walkers: a body and a closed route each, drawn from the seed: through a point NEAR
//! metres in front of the camera at a random instant (beside it where the floor in front has no
//! room) and two random free points, each leg the shortest way over the free floor (A* on the
//! floor map), smoothed. The walker is timed to reach the camera then, and gives way like a
//! person: at every instant it walks on, waits or steps back, whichever keeps it clear of the
//! camera and the walkers planned before it. A route that does not fit is drawn again, and so
//! is one that would leave the walker pacing a corner or standing to give way most of the time
//! (the nearest to walking through the room is kept when none does, unless it would stand three
//! quarters of the time). "Every instant": positions are compared every [`CHECK_STEP_S`] seconds
//! with a margin of the distance two things can close in half a step, so no contact can hide
//! between two checks.

use glam::{Vec2, Vec3};

use super::floor_map::FloorMap;
use super::footprint::{point_segment_distance, segment_distance, Footprint};
use super::walk_path::{Route, WalkPath};
use super::walker::{WalkerBody, MAX_STRIDE};
use super::{RigidActor, Walker};
use crate::scene::builtin::rng::Rng;

/// Metres kept between a walker's body and the camera centre.
pub const CAMERA_CLEARANCE: f32 = 0.1;
/// Metres at most between the points of a line checked for clearance: a line of sight, a
/// route's poses along a straight piece, the points of a footprint's axis.
const CLEARANCE_STEP: f32 = 0.025;
/// What a walker may do in a check step, as multiples of its speed: walk on, hurry, wait, step
/// back, step back quickly.
const MOVES: [f32; 5] = [1.0, 1.5, 0.0, -1.0, -1.5];
/// Seconds a walker looks ahead to give way, in this many steps.
const LOOK_AHEAD_S: f64 = 1.0;
const LOOK_AHEAD_STEPS: usize = 10;
/// Starts tried either side of the one that meets the camera on time, this many metres apart.
const START_SHIFTS: usize = 21;
const START_SHIFT_M: f32 = 0.1;
/// Draws of a stop before the free floor counts as too small for a route.
const STOP_DRAWS: usize = 200;
/// Stops are drawn in front of the camera: this far, metres ...
const VIEW_DISTANCE: (f32, f32) = (1.0, 4.0);
/// ... and within this angle of its axis over the floor, radians.
const VIEW_HALF_ANGLE: f32 = 0.6;
/// Metres at least between a route's stops.
const STOP_SPACING: f32 = 1.0;
/// The point passed near the camera lies within this angle of its axis over the floor, radians
/// (inside TUM's and Replica's views, 31° and 45° either side) ...
const PASSING_HALF_ANGLE: f32 = 0.5;
/// ... in a band this many metres wide beyond NEAR (or the nearest the floor has room for).
const PASSING_BAND: f32 = 0.25;
/// A walker meeting the camera in its view must come within NEAR while its centre lies within
/// this angle of the camera's axis over the floor, radians (giving way shifts the meeting a
/// little).
pub const SEEN_HALF_ANGLE: f32 = 0.7;
/// ... and nearer than this many metres (a body farther away covers little of the frame).
pub const SEEN_DISTANCE: f32 = 4.0;
/// Metres a footprint's ends can swing in half a check step as the walker turns.
const TURN_MARGIN: f32 = 0.01;
/// Metres kept between two walkers' bodies.
const WALKER_GAP: f32 = 0.05;
/// Seconds between the instants compared.
pub(super) const CHECK_STEP_S: f64 = 0.005;
/// Paths tried per walker before the floor counts as too crowded ...
const ATTEMPTS: usize = 400;
/// ... in each of this many draws of all the walkers.
const REDRAWS: usize = 8;
/// Metres nearer the walker ahead is tried each time its AHEAD leaves it no way.
const AHEAD_STEP_M: f32 = 0.25;
/// The nearest the walker ahead is tried: an arm's length past its body (the least AHEAD asked).
const LEAST_AHEAD_M: f32 = 0.9;
/// Waypoints of a route besides the one near the camera, at most (at least one: a walk there
/// and back).
const WAYPOINTS: usize = 2;
/// A walk walks through the room when its route spans this many metres at least (between its
/// two farthest points) ...
const LEAST_ROUTE_SPAN: f32 = 2.0;
/// ... and the walker walks on this share of the time at least ([`walking_share`]). The first
/// such walk drawn is kept; where none is, the one nearest it of the first [`WALKS_COMPARED`]
/// that fit: one that walks enough to be planned ([`LEAST_WALKING_SHARE_PLANNED`]) before one
/// that does not, then one that spans the room, then the one that walks most. Taking the first
/// walk that fit, 30 of 105 walkers at severity 5 (five draws on seven scenes) walked less than
/// half the time, a standing person being part of the static scene, and others paced a metre
/// back and forth.
const LEAST_WALKING_SHARE: f32 = 0.8;
const WALKS_COMPARED: usize = 24;
/// A walker that would walk less than this share of the time does not fit (it would stand in
/// the room, a part of the static scene), and all the walkers are drawn again.
const LEAST_WALKING_SHARE_PLANNED: f32 = 0.25;
/// Seconds over which a walker counts as walking on: getting on at half its speed or more, not
/// waiting, stepping back or edging forward by turns.
const PROGRESS_WINDOW_S: f64 = 0.25;
/// Metres of clearance the shortest ways keep beyond the body's radius.
pub(super) const ROUTE_MARGIN: f32 = 0.05;
/// How much farther than NEAR a walker's closest approach may stay, metres (giving way moves
/// the meeting).
const NEAR_TOLERANCE: f32 = 0.15;
/// The tallest body a walker may have, metres (`WalkerBody::new` stays under it).
pub(super) const TALLEST: f32 = 1.95;

/// How many walkers, how fast and how near the camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WalkerParams {
    pub count: u32,
    pub speed_m_s: f32,
    /// Closest approach of each walker's body (its footprint's edge) to the camera centre,
    /// metres.
    pub near_m: f32,
    /// How far in front of the camera one of them keeps all along instead ([`super::ahead`]):
    /// metres from the camera centre to its axis, or as near that as the floor in view allows.
    pub ahead_m: Option<f32>,
}

/// The camera's centre over the sequence: positions at increasing times (seconds), linear
/// between them. A rig's body path stands for all its cameras.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraTrack {
    pub times: Vec<f64>,
    pub positions: Vec<Vec3>,
    /// Where the camera looks at each time: its optical axis in world coordinates.
    pub axes: Vec<Vec3>,
}

impl CameraTrack {
    pub fn at(&self, t: f64) -> Vec3 {
        let i = self.times.partition_point(|&x| x <= t);
        if i == 0 {
            return self.positions[0];
        }
        if i == self.times.len() {
            return *self
                .positions
                .last()
                .expect("a camera track has a position");
        }
        let (t0, t1) = (self.times[i - 1], self.times[i]);
        let f = ((t - t0) / (t1 - t0)) as f32;
        self.positions[i - 1].lerp(self.positions[i], f)
    }

    /// Where the camera looks at `t`: the axis of the pose at or before it.
    pub fn axis_at(&self, t: f64) -> Vec3 {
        let i = self.times.partition_point(|&x| x <= t).max(1) - 1;
        self.axes[i.min(self.axes.len() - 1)]
    }

    /// Every [`CHECK_STEP_S`] from 0 to the end of its time: the instants things are checked at.
    pub(super) fn instants(&self) -> impl Iterator<Item = f64> {
        let steps = (self.duration() / CHECK_STEP_S).ceil() as usize;
        (0..=steps).map(|k| k as f64 * CHECK_STEP_S)
    }

    pub(super) fn duration(&self) -> f64 {
        self.times.last().copied().unwrap_or(0.0)
    }

    /// The fastest the camera moves over the floor, metres per second.
    pub(super) fn top_speed(&self) -> f32 {
        (1..self.times.len())
            .map(|i| {
                let d = (self.positions[i] - self.positions[i - 1])
                    .truncate()
                    .length();
                d / (self.times[i] - self.times[i - 1]).max(1e-9) as f32
            })
            .fold(0.0, f32::max)
    }
}

/// Who walks: people (`actors`), or people carrying a box (`objects`), drawn from streams of
/// their own.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Walking {
    Freely,
    Carrying,
}

/// `params.count` more walkers over the floor `map` (of the walkers' height), after `walkers`,
/// giving way to them and to the user's `rigid` actors (who keep their way), or why they do not
/// fit. Where one does not fit, all of them are drawn again from a stream of their own, up to
/// [`REDRAWS`] times: an earlier walker's route can leave a later one no way.
pub(super) fn walkers(
    map: &FloorMap,
    (params, walking): (&WalkerParams, Walking),
    seed: u64,
    camera: &CameraTrack,
    (walkers, rigid): (Vec<Walker>, &[RigidActor]),
) -> Result<Vec<Walker>, String> {
    if camera.times.is_empty() {
        return Err("people need the camera's path to keep clear of, and it is empty".into());
    }
    let (first, who) = match walking {
        Walking::Freely => (Rng::new(seed).fork("actors"), "walker"),
        Walking::Carrying => (Rng::new(seed).fork("carriers"), "box carrier"),
    };
    let mut unplaced = 0;
    for ahead_m in aheads(params.ahead_m) {
        let params = &WalkerParams { ahead_m, ..*params };
        for redraw in 0..REDRAWS {
            let rng = match redraw {
                0 => first.clone(),
                _ => first.fork(&format!("redraw {redraw}")),
            };
            match draw(
                map,
                (params, walking),
                &rng,
                camera,
                (walkers.clone(), rigid),
            ) {
                Ok(placed) => return Ok(placed),
                Err(k) => unplaced = unplaced.max(k),
            }
        }
        if unplaced > 0 {
            break;
        }
    }
    if let (Some(ahead), 0) = (params.ahead_m, unplaced) {
        return Err(format!(
            "the {who} ahead of the camera: the floor the camera looks over leaves it no way clear of the furniture and the camera, {ahead} m ahead or nearer down to {LEAST_AHEAD_M} m (all the {who}s drawn {REDRAWS} times at each); ask for none ahead"
        ));
    }
    Err(format!(
        "{who} {} of {}: no path over the free floor keeps clear of the furniture, the camera and the other walkers (walking a quarter of the time or more) in {ATTEMPTS} tries, with all of them drawn {REDRAWS} times; ask for fewer walkers",
        unplaced + 1,
        params.count,
    ))
}

/// How far ahead of the camera the walker ahead is tried, if there is one: AHEAD, then nearer
/// by [`AHEAD_STEP_M`] down to [`LEAST_AHEAD_M`], as a walker passes as near as the floor has
/// room for (on room2 no way 2 m ahead keeps clear of the furniture and the camera, 1.5 m does).
fn aheads(ahead_m: Option<f32>) -> Vec<Option<f32>> {
    match ahead_m {
        None => vec![None],
        Some(a) => (0..)
            .map(|k| a - k as f32 * AHEAD_STEP_M)
            .take_while(|&d| d >= LEAST_AHEAD_M - 1e-3)
            .map(Some)
            .collect(),
    }
}

/// One draw of `params.count` walkers from `rng` after `walkers` (first the one ahead of the
/// camera, if asked), or the index of the first that does not fit.
fn draw(
    map: &FloorMap,
    (params, walking): (&WalkerParams, Walking),
    rng: &Rng,
    camera: &CameraTrack,
    (mut walkers, rigid): (Vec<Walker>, &[RigidActor]),
) -> Result<Vec<Walker>, usize> {
    let mut passing = params.count as usize;
    if let Some(ahead) = params.ahead_m {
        let dressed = Dressed::drawn(&mut rng.fork("walker ahead"), (params, walking));
        let speed_ahead = (params.speed_m_s, ahead);
        let walked =
            super::ahead::walker_ahead(map, &dressed.footprint, speed_ahead, camera, rigid)
                .ok_or(0_usize)?;
        walkers.push(dressed.walking(walked, Some(ahead)));
        passing -= 1;
    }
    let first = params.count as usize - passing;
    for k in 0..passing {
        let mut rng = rng.fork(&format!("walker {k}"));
        let dressed = Dressed::drawn(&mut rng, (params, walking));
        let footprint = dressed.footprint;
        let floor = WalkableFloor::of(map, &footprint);
        let mut nearest: Option<((bool, bool, f32), Walk)> = None;
        let mut fitted = 0;
        for attempt in 0..ATTEMPTS {
            let in_front = attempt < ATTEMPTS / 2;
            let Some((route, meeting)) =
                try_route(&mut rng, &floor, &footprint, (params, in_front), camera)
            else {
                continue;
            };
            let spans = span(route.points()) >= LEAST_ROUTE_SPAN;
            let Some(walked) = walk(
                route,
                meeting,
                (&footprint, params),
                camera,
                (&walkers, rigid),
            ) else {
                continue;
            };
            fitted += 1;
            let merit = (
                walked.walking_share >= LEAST_WALKING_SHARE_PLANNED,
                spans,
                walked.walking_share,
            );
            let through_the_room = spans && walked.walking_share >= LEAST_WALKING_SHARE;
            if nearest.as_ref().is_none_or(|(best, _)| merit > *best) {
                nearest = Some((merit, walked));
            }
            if through_the_room || fitted == WALKS_COMPARED {
                break;
            }
        }
        let (_, walked) = nearest
            .filter(|(_, walked)| walked.walking_share >= LEAST_WALKING_SHARE_PLANNED)
            .ok_or(first + k)?;
        walkers.push(dressed.walking(walked, None));
    }
    Ok(walkers)
}

/// Metres two things moving at `speed` and `other_speed` m/s at most can close in half a check
/// step, with what a footprint's ends swing as it turns.
pub(super) fn closing(speed: f32, other_speed: f32) -> f32 {
    (speed + other_speed) * CHECK_STEP_S as f32 / 2.0 + TURN_MARGIN
}

/// What a walker with `footprint`, at most `top_speed` m/s, keeps clear of: the camera, the
/// walkers planned before it and the user's rigid actors, each with the margin the two can close
/// in half a check step.
pub(super) struct Surroundings<'a> {
    footprint: &'a Footprint,
    top_speed: f32,
    camera: &'a CameraTrack,
    camera_gap: f32,
    others: &'a [Walker],
    rigid: &'a [RigidActor],
    rigid_speeds: Vec<f32>,
}

impl<'a> Surroundings<'a> {
    pub(super) fn new(
        (footprint, top_speed): (&'a Footprint, f32),
        camera: &'a CameraTrack,
        (others, rigid): (&'a [Walker], &'a [RigidActor]),
    ) -> Self {
        Self {
            footprint,
            top_speed,
            camera,
            camera_gap: footprint.radius
                + CAMERA_CLEARANCE
                + closing(top_speed, camera.top_speed()),
            others,
            rigid,
            rigid_speeds: rigid.iter().map(RigidActor::top_speed).collect(),
        }
    }

    /// Metres the body keeps between itself and the camera's centre, at least.
    pub(super) fn camera_gap(&self) -> f32 {
        self.camera_gap
    }

    /// Metres to spare for the footprint's segment `[a, b]` at time `t` (negative: too close).
    pub(super) fn room(&self, [a, b]: [Vec2; 2], t: f64) -> f32 {
        let radius = self.footprint.radius;
        let to_camera =
            point_segment_distance(self.camera.at(t).truncate(), a, b) - self.camera_gap;
        let walkers = self.others.iter().fold(to_camera, |least, o| {
            let gap =
                radius + o.footprint.radius + WALKER_GAP + closing(self.top_speed, o.path.speed());
            let (there, facing) = o.path.facing_at(t);
            least.min(segment_distance([a, b], o.footprint.segment_facing(there, facing)) - gap)
        });
        (self.rigid.iter().zip(&self.rigid_speeds)).fold(walkers, |least, (r, &r_speed)| {
            let gap = radius + r.radius + WALKER_GAP + closing(self.top_speed, r_speed);
            least.min(point_segment_distance(r.pose_at(t).1.truncate(), a, b) - gap)
        })
    }
}

/// A walker's body, what it wears and what it covers of the floor, before it walks.
struct Dressed {
    body: WalkerBody,
    colours: [[f32; 3]; 6],
    top: usize,
    stride: f32,
    footprint: Footprint,
}

impl Dressed {
    /// A body and its clothes drawn from `rng`, stepping at the stride of `params`' speed.
    fn drawn(rng: &mut Rng, (params, walking): (&WalkerParams, Walking)) -> Self {
        let body = match walking {
            Walking::Freely => WalkerBody::new(rng),
            Walking::Carrying => WalkerBody::new(rng).carrying(rng),
        };
        let mut colours = clothing(rng);
        // From a stream of its own: the walks drawn after it stay as they were.
        let top = top(&mut rng.fork("top"));
        if top != 0 {
            colours[0] = [1.0; 3];
        }
        let stride = stride_of(params.speed_m_s, body.height());
        let footprint = Footprint::of(&body, stride);
        Self {
            body,
            colours,
            top,
            stride,
            footprint,
        }
    }

    /// The walker walking `walked`, keeping `ahead` metres in front of the camera if it does.
    fn walking(self, walked: Walk, ahead: Option<f32>) -> Walker {
        Walker {
            body: self.body,
            footprint: self.footprint,
            path: walked.path,
            stride: self.stride,
            colours: self.colours,
            top: self.top,
            closest_m: walked.closest_m,
            closest_in_view_m: walked.closest_in_view_m,
            walking_share: walked.walking_share,
            in_view_share: walked.in_view_share,
            ahead_m: ahead,
        }
    }
}

/// Whether the floor point `p` lies in front of a camera at `eye` looking along `axis`, between
/// [`VIEW_DISTANCE`] metres and within [`VIEW_HALF_ANGLE`] of the axis over the floor.
pub(super) fn in_view(eye: Vec3, axis: Vec3, p: Vec2) -> bool {
    let (eye, forward) = (eye.truncate(), axis.truncate().normalize_or_zero());
    (VIEW_DISTANCE.0..VIEW_DISTANCE.1).contains(&p.distance(eye))
        && within_angle((eye, forward), p, VIEW_HALF_ANGLE)
}

/// Whether the floor point `p` lies within `half_angle` radians of the unit direction
/// `forward` seen from `eye`.
pub(super) fn within_angle((eye, forward): (Vec2, Vec2), p: Vec2, half_angle: f32) -> bool {
    let to = p - eye;
    to.dot(forward) >= to.length() * half_angle.cos()
}

/// A free cell of `free` at least `beside` metres from `eye`, drawn from the nearest
/// [`PASSING_BAND`] of them; with a `forward` direction over the floor, only cells within
/// [`PASSING_HALF_ANGLE`] of it count. `None` when no cell does.
pub(super) fn passing_point(
    rng: &mut Rng,
    free: &[Vec2],
    (eye, forward): (Vec2, Option<Vec2>),
    beside: f32,
) -> Option<Vec2> {
    let ahead = |p: Vec2| forward.is_none_or(|f| within_angle((eye, f), p, PASSING_HALF_ANGLE));
    let mut beyond: Vec<(f32, Vec2)> = (free.iter())
        .map(|&p| (p.distance(eye), p))
        .filter(|&(d, p)| d >= beside && ahead(p))
        .collect();
    beyond.sort_by(|a, b| a.0.total_cmp(&b.0));
    let nearest = beyond.first()?.0;
    let band = beyond.partition_point(|(d, _)| *d < nearest + PASSING_BAND);
    Some(beyond[rng.int(0, band as i64) as usize].1)
}

/// The largest distance between two of `points`.
fn span(points: &[Vec2]) -> f32 {
    (points.iter().enumerate())
        .flat_map(|(i, p)| points[i + 1..].iter().map(move |q| p.distance(*q)))
        .fold(0.0, f32::max)
}

/// Pieces a line `length` metres long is cut into to check its clearance every
/// [`CLEARANCE_STEP`] at most.
fn clearance_checks(length: f32) -> usize {
    (length / CLEARANCE_STEP).ceil().max(1.0) as usize
}

/// The points of `way` where it must turn: each kept point sees the next one over cells with
/// `clearance` all along the straight line between them.
pub(super) fn corners(map: &FloorMap, way: &[Vec2], clearance: f32) -> Vec<Vec2> {
    let sees = |a: Vec2, b: Vec2| {
        let pieces = clearance_checks(a.distance(b));
        (0..=pieces).all(|i| map.clearance(a.lerp(b, i as f32 / pieces as f32)) >= clearance)
    };
    let mut kept = vec![way[0]];
    let mut i = 0;
    while i + 1 < way.len() {
        let mut j = i + 1;
        while j + 1 < way.len() && sees(way[i], way[j + 1]) {
            j += 1;
        }
        kept.push(way[j]);
        i = j;
    }
    kept.pop();
    kept
}

/// A step length for `speed` (people lengthen their steps as they walk faster: about 0.65 m
/// at 1.2 m/s for a 1.75 m adult), within what the body allows.
fn stride_of(speed: f32, height: f32) -> f32 {
    ((0.3 + 0.3 * speed) * height / 1.75).clamp(0.2, MAX_STRIDE)
}

/// Where one walker can go: the ways it takes keep its width (the footprint's radius) and a
/// margin clear of the scene (`passage`), over the largest region of cells with that much
/// room; it turns (and so stops) only on `turning` cells of that region, where the scene keeps
/// out of the circle its footprint turns in. Whether its footprint, facing the way it walks,
/// fits all along a route is checked on the route ([`clears_the_scene`]): a walker needs no
/// room to turn round where it does not turn.
struct WalkableFloor<'a> {
    map: &'a FloorMap,
    passage: f32,
    turning: Vec<Vec2>,
}

impl<'a> WalkableFloor<'a> {
    fn of(map: &'a FloorMap, footprint: &Footprint) -> Self {
        let passage = footprint.radius + ROUTE_MARGIN;
        let turning = room_to_turn(map, &map.largest_region(passage), footprint);
        Self {
            map,
            passage,
            turning,
        }
    }
}

/// The points of `region` where the scene keeps out of the whole circle `footprint` turns in.
pub(super) fn room_to_turn(map: &FloorMap, region: &[Vec2], footprint: &Footprint) -> Vec<Vec2> {
    let turn = footprint.radius + footprint.half_length + ROUTE_MARGIN;
    (region.iter().copied())
        .filter(|&p| map.clearance(p) >= turn)
        .collect()
}

/// Whether the scene keeps out of `footprint` all along `route`, facing the way it goes: the
/// route is straight between its dense samples, so its poses are checked every
/// [`CLEARANCE_STEP`] metres along each straight piece, on points of the footprint's segment as
/// far apart, with the margin both steps leave (the floor map's clearance of a point bounds
/// every point of its cell).
pub(super) fn clears_the_scene(map: &FloorMap, route: &Route, footprint: &Footprint) -> bool {
    let need = footprint.radius + CLEARANCE_STEP;
    let axis = clearance_checks(2.0 * footprint.half_length);
    route.pieces().all(|(a, b, facing)| {
        let poses = clearance_checks(a.distance(b));
        (0..=poses).all(|i| {
            let [tail, head] = footprint.segment_facing(a.lerp(b, i as f32 / poses as f32), facing);
            (0..=axis).all(|j| map.clearance(tail.lerp(head, j as f32 / axis as f32)) >= need)
        })
    })
}

/// Where the walker meets the camera: metres along its route, and when.
struct Meeting {
    along: f32,
    time: f64,
    /// How near the camera the walker's body comes there, metres: NEAR, or more where the
    /// floor has no room that near.
    near: f32,
    /// Whether it meets the camera in its view (else anywhere round it).
    in_view: bool,
}

/// A closed route through a point `near_m` from the camera at a random instant (in front of it
/// when `in_front`, else anywhere round it) and [`WAYPOINTS`] random free points, each leg the
/// shortest way between them over the free floor, smoothed; `None` when no such route fits the
/// body.
fn try_route(
    rng: &mut Rng,
    floor: &WalkableFloor,
    footprint: &Footprint,
    (params, in_front): (&WalkerParams, bool),
    camera: &CameraTrack,
) -> Option<(Route, Meeting)> {
    let WalkableFloor {
        map,
        passage,
        turning: free,
    } = floor;
    let passage = *passage;
    let beside = params.near_m + footprint.radius;
    // A free cell NEAR from the camera at a random instant, or as near as the floor allows.
    let time = f64::from(rng.range(0.05, 0.95)) * camera.duration();
    let eye = camera.at(time).truncate();
    let forward = in_front.then(|| camera.axis_at(time).truncate().normalize_or_zero());
    let meeting = passing_point(rng, free, (eye, forward), beside)?;
    let near = params.near_m.max(meeting.distance(eye) - footprint.radius);
    // The other stops lie where the camera looks at random instants, so the walker crosses
    // the view, as people walk round in front of the camera in TUM's and Bonn's sequences.
    let mut stops = vec![meeting];
    for _ in 0..STOP_DRAWS {
        let p = free[rng.int(0, free.len() as i64) as usize];
        let k = rng.int(0, camera.times.len() as i64) as usize;
        if !in_view(camera.positions[k], camera.axes[k], p) {
            continue;
        }
        if stops.iter().all(|q| q.distance(p) > STOP_SPACING) {
            stops.push(p);
        }
        if stops.len() > WAYPOINTS {
            break;
        }
    }
    if stops.len() < 2 {
        return None;
    }
    let mut way = Vec::new();
    for (i, &from) in stops.iter().enumerate() {
        let leg = map.way(from, stops[(i + 1) % stops.len()], passage)?;
        way.extend(corners(map, &leg[..leg.len() - 1], passage));
    }
    let route = Route::new(&way);
    if !clears_the_scene(map, &route, footprint) {
        return None;
    }
    let along = route.arc_length_to(meeting);
    Some((
        route,
        Meeting {
            along,
            time,
            near,
            in_view: in_front,
        },
    ))
}

/// A walker's timing on its route, the closest it comes to the camera (metres; anywhere, and in
/// front of it), the share of the time it walks on ([`walking_share`]) and the share it is in
/// front of the camera.
pub(super) struct Walk {
    pub(super) path: WalkPath,
    closest_m: f32,
    /// The closest it comes while in front of the camera ([`SEEN_HALF_ANGLE`]); `None` when it
    /// never is.
    closest_in_view_m: Option<f32>,
    walking_share: f32,
    /// The share of the instants its centre is in front of the camera ([`SEEN_HALF_ANGLE`]),
    /// under [`SEEN_DISTANCE`] away.
    in_view_share: f32,
}

impl Walk {
    /// `path` walked by a body of `footprint` as the camera on `camera` sees it, at every
    /// [`CHECK_STEP_S`].
    pub(super) fn timed(path: WalkPath, footprint: &Footprint, camera: &CameraTrack) -> Self {
        let (mut closest, mut closest_seen, mut seen, mut instants) =
            (f32::INFINITY, f32::INFINITY, 0, 0);
        for t in camera.instants() {
            let (p, facing) = path.facing_at(t);
            let [a, b] = footprint.segment_facing(p, facing);
            let eye = camera.at(t).truncate();
            let body_to_camera = point_segment_distance(eye, a, b) - footprint.radius;
            closest = closest.min(body_to_camera);
            let forward = camera.axis_at(t).truncate().normalize_or_zero();
            if within_angle((eye, forward), p, SEEN_HALF_ANGLE) {
                closest_seen = closest_seen.min(body_to_camera);
                seen += usize::from(p.distance(eye) <= SEEN_DISTANCE);
            }
            instants += 1;
        }
        Self {
            closest_m: closest,
            closest_in_view_m: closest_seen.is_finite().then_some(closest_seen),
            walking_share: walking_share(path.along(), path.speed()),
            in_view_share: seen as f32 / instants as f32,
            path,
        }
    }
}

/// The walker's timing on `route`: timed to reach the meeting point at the meeting time, it
/// walks on at its speed while that stays clear of the camera and of every walker in `others`
/// for the next [`LOOK_AHEAD_S`]; otherwise it hurries, waits or steps back, whichever keeps
/// the most room over that time (earlier walkers' timings are known). `None` when no move
/// keeps it clear at the next instant, or when it never comes within `near_m` of the camera
/// (while in its view, for a meeting in view).
fn walk(
    route: Route,
    meeting: Meeting,
    (footprint, params): (&Footprint, &WalkerParams),
    camera: &CameraTrack,
    (others, rigid): (&[Walker], &[RigidActor]),
) -> Option<Walk> {
    let speed = params.speed_m_s;
    let around = Surroundings::new((footprint, speed * MOVES[1]), camera, (others, rigid));
    // Metres to spare at `s` along the route at time `t` (negative: too close).
    let room = |s: f32, t: f64| {
        let (p, facing) = route.facing_at(s);
        around.room(footprint.segment_facing(p, facing), t)
    };
    // The least room over the look-ahead, moving on at `pace` times the speed from `s`.
    let foresight = |s: f32, t: f64, pace: f32| {
        (1..=LOOK_AHEAD_STEPS)
            .map(|k| {
                let dt = k as f64 * LOOK_AHEAD_S / LOOK_AHEAD_STEPS as f64;
                room(s + pace * speed * dt as f32, t + dt)
            })
            .fold(f32::INFINITY, f32::min)
    };
    let step = speed * CHECK_STEP_S as f32;
    let steps = (camera.duration() / CHECK_STEP_S).ceil() as usize + 1;
    // Timed to reach the meeting point then, or as near that as leaves it clear at the start.
    let on_time = meeting.along - speed * meeting.time as f32;
    let mut s = (0..START_SHIFTS)
        .map(|k| {
            let shift = if k % 2 == 0 { k / 2 } else { k.div_ceil(2) } as f32;
            on_time + START_SHIFT_M * if k % 2 == 0 { shift } else { -shift }
        })
        .find(|&s| room(s, 0.0) >= 0.0)?;
    let mut along = Vec::with_capacity(steps);
    for i in 0..steps {
        let t = i as f64 * CHECK_STEP_S;
        if i > 0 {
            let clear = |&pace: &f32| room(s + pace * step, t) >= 0.0;
            let pace = if clear(&1.0) && foresight(s, t, 1.0) >= 0.0 {
                1.0
            } else {
                let best = MOVES
                    .iter()
                    .filter(|p| clear(p))
                    .max_by(|a, b| foresight(s, t, **a).total_cmp(&foresight(s, t, **b)));
                *best?
            };
            s += pace * step;
        }
        along.push(s);
    }
    let walked = Walk::timed(
        WalkPath::new(route, speed, CHECK_STEP_S, along),
        footprint,
        camera,
    );
    let closest_met = if meeting.in_view {
        walked.closest_in_view_m.unwrap_or(f32::INFINITY)
    } else {
        walked.closest_m
    };
    (closest_met <= meeting.near + NEAR_TOLERANCE).then_some(walked)
}

/// The share of the instants `along` (metres along the route every [`CHECK_STEP_S`]) from
/// which the walker gets on at half its `speed` or more over the next [`PROGRESS_WINDOW_S`].
fn walking_share(along: &[f32], speed: f32) -> f32 {
    let window = (PROGRESS_WINDOW_S / CHECK_STEP_S).round() as usize;
    let progress = speed * PROGRESS_WINDOW_S as f32 / 2.0;
    let starts = along.len().saturating_sub(window).max(1);
    let walking = (along.windows(window + 1))
        .filter(|w| w[window] - w[0] >= progress)
        .count();
    walking as f32 / starts as f32
}

/// A walker's top ([`Walker::top`]): plain cloth for 40 %, else one of the patterned tops
/// (stripes, checks, a print); the share is chosen, not measured.
fn top(rng: &mut Rng) -> usize {
    const PLAIN_SHARE: f32 = 0.4;
    let patterned = crate::scene::builtin::PATTERNED_TOPS;
    if rng.f32() < PLAIN_SHARE {
        0
    } else {
        rng.int(patterned.start as i64, patterned.end as i64) as usize
    }
}

/// Colours of a walker's top, trousers, skin, hair and shoes (the order of
/// [`super::BodyMaterial`]), sRGB: muted everyday clothes.
fn clothing(rng: &mut Rng) -> [[f32; 3]; 6] {
    const TOPS: [[f32; 3]; 8] = [
        [0.16, 0.2, 0.34],
        [0.55, 0.56, 0.58],
        [0.62, 0.18, 0.16],
        [0.9, 0.9, 0.88],
        [0.25, 0.38, 0.28],
        [0.12, 0.12, 0.13],
        [0.8, 0.66, 0.42],
        [0.38, 0.5, 0.68],
    ];
    const TROUSERS: [[f32; 3]; 5] = [
        [0.2, 0.27, 0.42],
        [0.1, 0.1, 0.11],
        [0.6, 0.54, 0.4],
        [0.35, 0.36, 0.38],
        [0.28, 0.22, 0.18],
    ];
    const SKIN: [[f32; 3]; 5] = [
        [0.96, 0.8, 0.69],
        [0.88, 0.68, 0.55],
        [0.76, 0.55, 0.4],
        [0.55, 0.38, 0.27],
        [0.36, 0.24, 0.17],
    ];
    const HAIR: [[f32; 3]; 4] = [
        [0.08, 0.06, 0.05],
        [0.3, 0.2, 0.12],
        [0.72, 0.6, 0.38],
        [0.6, 0.6, 0.6],
    ];
    // Brown corrugated board.
    const CARTON: [f32; 3] = [0.66, 0.5, 0.33];
    const SHOES: [[f32; 3]; 3] = [[0.1, 0.1, 0.1], [0.35, 0.22, 0.14], [0.85, 0.85, 0.85]];
    let mut pick = |choices: &[[f32; 3]]| choices[rng.int(0, choices.len() as i64) as usize];
    [
        pick(&TOPS),
        pick(&TROUSERS),
        pick(&SKIN),
        pick(&HAIR),
        pick(&SHOES),
        CARTON,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four in ten tops plain, the rest spread over every patterned top.
    #[test]
    fn tops_are_plain_or_any_of_the_patterned_ones() {
        let draws = 3000;
        let mut counts = [0usize; crate::scene::builtin::PATTERNED_TOPS.end];
        for seed in 0..draws {
            counts[top(&mut Rng::new(seed))] += 1;
        }
        let plain = counts[0] as f32 / draws as f32;
        // Three standard errors of a share of 0.4 over 3000 draws: 0.027.
        assert!((plain - 0.4).abs() < 0.027, "{plain} plain");
        let patterned = &counts[crate::scene::builtin::PATTERNED_TOPS];
        assert!(patterned.iter().all(|&n| n > 60), "{patterned:?}");
        assert_eq!(counts[1..3], [0, 0], "trousers and shoes are no top");
    }
}
