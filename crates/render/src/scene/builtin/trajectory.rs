//! Default trajectories: a hand-held walk twice round a scene's free "track", like the Replica and
//! TUM sequences: the walker slows down, nearly stops and speeds up again; the view turns on its own
//! clock, so the camera sometimes turns almost in place; it looks across the room, obliquely along
//! the walls, at the nearest (often plain) wall from the edge of the track, and up into a ceiling
//! corner.
//!
//! Waypoints sit on an ellipse inside the track, ten a lap (radius and height jittered per scene); the path
//! is a periodic Catmull–Rom spline through them. Each waypoint has a look-at target; targets are
//! splined too, walked with a progress of their own, and slow sinusoids add hand-held yaw, pitch,
//! roll and position wobble.

use std::f32::consts::TAU;

use glam::{DMat3, DQuat, DVec3, Vec2, Vec3};
use rslam_core::{Pose, Trajectory};

use super::rng::Rng;

pub const FRAMES: usize = 2000;
pub const RATE_HZ: f64 = rslam_core::REPLICA_RATE_HZ;
/// Twice round the room in a sequence: a mean walking speed of about 0.2 m/s and turns of about
/// 20°/s, as in hand-held TUM sequences (fr1: 0.2–0.4 m/s, 9–30°/s), with the second lap on
/// waypoints of its own.
const LAPS: usize = 2;
const WAYPOINTS_PER_LAP: usize = 10;
const WAYPOINTS: usize = LAPS * WAYPOINTS_PER_LAP;
/// Dense spline samples per waypoint for the arc-length table.
const SAMPLES_PER_SPAN: usize = 64;

/// The free floor area the camera may roam (kept clear of anything taller than ~0.9 m) and the
/// room's extent, from which look-at targets are chosen.
#[derive(Clone, Copy, Debug)]
pub struct Track {
    pub centre: Vec2,
    pub half: Vec2,
    /// Half extent of the room (targets lie inside it).
    pub room_half: Vec2,
    /// Ceiling height, metres.
    pub height: f32,
}

/// A walk round `track`: `FRAMES` poses at `RATE_HZ`, deterministic in `seed`; it starts
/// `start_offset` laps (0..1) further round the track than the seed alone would put it.
pub fn default_trajectory(track: &Track, seed: u64, start_offset: f32) -> Trajectory {
    let mut rng = Rng::new(seed);
    let start = (rng.f32() + start_offset) * TAU;
    let direction = if rng.chance(0.5) { 1.0 } else { -1.0 };
    let mut points = Vec::with_capacity(WAYPOINTS);
    let mut targets = Vec::with_capacity(WAYPOINTS);
    for k in 0..WAYPOINTS {
        let a = start + direction * TAU * k as f32 / WAYPOINTS_PER_LAP as f32;
        let radial = Vec2::new(a.cos(), a.sin());
        let kind = View::of_waypoint(k);
        let r = match kind {
            View::NearestWall => 1.0,
            _ => rng.range(0.55, 1.0),
        };
        let p = track.centre + radial * track.half * r;
        let eye_height = rng.range(1.4, 1.75);
        points.push(p.extend(eye_height));
        let look = match kind {
            View::Across => a + std::f32::consts::PI + rng.range(-0.9, 0.9),
            View::AlongWall => a + direction * rng.range(0.9, 1.6),
            View::NearestWall => a + direction * rng.range(0.6, 0.9),
            View::CeilingCorner => a + direction * rng.range(0.5, 0.9),
        };
        let target = wall_target(track, p, look);
        targets.push(
            target.extend(match kind {
                // 10–18° up, at most to the ceiling.
                View::CeilingCorner => (eye_height
                    + target.distance(p) * rng.range(0.17, 0.31).tan())
                .min(track.height - 0.05),
                View::NearestWall => rng.range(1.2, 1.6),
                _ => rng.range(0.55, 1.1),
            }),
        );
    }
    let path = Spline::new(points, Vec3::ZERO);
    let turns = winding(&path.points, &targets);
    let aim = Spline::new(look_angles(&path.points, &targets), Vec3::X * TAU * turns);
    let lengths = path.arc_lengths();
    let total = *lengths.last().unwrap_or(&0.0);
    let walk = Progress::new(&mut rng, 0.8);
    let turn = Progress::new(&mut rng, 0.45);
    let wobble = Wobble::new(&mut rng);
    let poses = (0..FRAMES)
        .map(|i| {
            let tau = i as f32 / FRAMES as f32;
            let s = spline_parameter(&lengths, walk.at(tau) * total);
            let t = i as f32 / RATE_HZ as f32;
            let angles = aim.at(turn.at(tau) * WAYPOINTS as f32);
            let [yaw, pitch, roll] = wobble.angles(t);
            look_pose(
                path.at(s) + wobble.offset(t),
                angles.x + yaw,
                angles.y + pitch,
                roll,
            )
        })
        .collect();
    Trajectory::from_poses_at_rate(poses, RATE_HZ)
}

/// What the camera looks at from a waypoint.
#[derive(Clone, Copy, Debug, PartialEq)]
enum View {
    /// The far side of the room.
    Across,
    /// Obliquely along the nearer walls.
    AlongWall,
    /// At the nearest wall, half turned, from the edge of the track.
    NearestWall,
    /// Up along a wall to where it meets the ceiling.
    CeilingCorner,
}

impl View {
    /// Each lap: one look at the nearest wall, one up to the ceiling.
    fn of_waypoint(k: usize) -> View {
        use View::*;
        [
            Across,
            AlongWall,
            NearestWall,
            Across,
            AlongWall,
            Across,
            AlongWall,
            CeilingCorner,
            Across,
            AlongWall,
        ][k % 10]
    }
}

/// Progress round the loop in [0, 1] over time τ ∈ [0, 1], at a speed that varies smoothly and
/// periodically between nearly stopped and about twice the mean (`depth` sets how far).
struct Progress {
    /// Cumulative progress at τ = k / STEPS, k = 0 ..= STEPS.
    table: Vec<f32>,
}

impl Progress {
    const STEPS: usize = 4096;

    fn new(rng: &mut Rng, depth: f32) -> Self {
        let (f1, f2) = (rng.int(3, 6) as f32, rng.int(7, 12) as f32);
        let (p1, p2) = (rng.f32() * TAU, rng.f32() * TAU);
        let speed = |tau: f32| {
            let wave = 0.7 * (TAU * f1 * tau + p1).sin() + 0.3 * (TAU * f2 * tau + p2).sin();
            (1.0 + depth * wave).max(0.05)
        };
        let mut table = Vec::with_capacity(Self::STEPS + 1);
        let mut sum = 0.0;
        table.push(0.0);
        for k in 0..Self::STEPS {
            sum += speed((k as f32 + 0.5) / Self::STEPS as f32);
            table.push(sum);
        }
        table.iter_mut().for_each(|v| *v /= sum);
        Self { table }
    }

    fn at(&self, tau: f32) -> f32 {
        let x = tau.clamp(0.0, 1.0) * Self::STEPS as f32;
        let k = (x.floor() as usize).min(Self::STEPS - 1);
        let f = x - k as f32;
        self.table[k] + (self.table[k + 1] - self.table[k]) * f
    }
}

/// The point where a ray from `p` in direction `angle` leaves the room, pulled back 10 %.
fn wall_target(track: &Track, p: Vec2, angle: f32) -> Vec2 {
    let d = Vec2::new(angle.cos(), angle.sin());
    let exit = |pos: f32, dir: f32, half: f32| {
        if dir.abs() < 1e-6 {
            f32::INFINITY
        } else {
            ((dir.signum() * half - pos) / dir).max(0.0)
        }
    };
    let t = exit(p.x, d.x, track.room_half.x).min(exit(p.y, d.y, track.room_half.y));
    p + d * t * 0.9
}

/// (heading, elevation) from each waypoint to its target, headings unwrapped so consecutive
/// waypoints turn the short way.
fn look_angles(points: &[Vec3], targets: &[Vec3]) -> Vec<Vec3> {
    let mut out: Vec<Vec3> = Vec::with_capacity(points.len());
    for (p, t) in points.iter().zip(targets) {
        let d = *t - *p;
        let mut yaw = d.y.atan2(d.x);
        if let Some(prev) = out.last() {
            yaw = prev.x + wrap_angle(yaw - prev.x);
        }
        out.push(Vec3::new(yaw, d.z.atan2(d.truncate().length()), 0.0));
    }
    out
}

/// Whole turns the unwrapped headings make around the loop (closing back to the first waypoint).
fn winding(points: &[Vec3], targets: &[Vec3]) -> f32 {
    let angles = look_angles(points, targets);
    let (first, last) = (angles[0].x, angles[angles.len() - 1].x);
    let closed = last + wrap_angle(first - last);
    ((closed - first) / TAU).round()
}

fn wrap_angle(a: f32) -> f32 {
    (a + std::f32::consts::PI).rem_euclid(TAU) - std::f32::consts::PI
}

/// Camera at `eye` with heading `yaw` (from world +x towards +y) and elevation `pitch`, rolled by
/// `roll` about its optical axis; radians.
fn look_pose(eye: Vec3, yaw: f32, pitch: f32, roll: f32) -> Pose {
    let (yaw, pitch) = (yaw as f64, pitch as f64);
    let forward = DVec3::new(
        pitch.cos() * yaw.cos(),
        pitch.cos() * yaw.sin(),
        pitch.sin(),
    );
    let right = forward.cross(DVec3::Z).normalize();
    let down = forward.cross(right);
    let rotation = DQuat::from_mat3(&DMat3::from_cols(right, down, forward));
    let rotation = rotation * DQuat::from_rotation_z(roll as f64);
    Pose::new(rotation, eye.as_dvec3())
}

/// Slow sinusoids: hand-held sway of position (metres) and of yaw, pitch, roll (radians).
struct Wobble {
    /// (amplitude, frequency Hz, phase) per component.
    terms: [[(f32, f32, f32); 2]; 6],
}

impl Wobble {
    fn new(rng: &mut Rng) -> Self {
        let amplitudes = [0.03, 0.03, 0.025, 0.2, 0.08, 0.05];
        let terms = std::array::from_fn(|c| {
            std::array::from_fn(|k| {
                let a = amplitudes[c] * if k == 0 { 1.0 } else { 0.35 };
                let f = if k == 0 {
                    rng.range(0.03, 0.08)
                } else {
                    rng.range(0.2, 0.45)
                };
                (a, f, rng.f32() * TAU)
            })
        });
        Self { terms }
    }

    fn component(&self, c: usize, t: f32) -> f32 {
        self.terms[c]
            .iter()
            .map(|(a, f, p)| a * (TAU * f * t + p).sin())
            .sum()
    }

    fn offset(&self, t: f32) -> Vec3 {
        Vec3::new(
            self.component(0, t),
            self.component(1, t),
            self.component(2, t),
        )
    }

    fn angles(&self, t: f32) -> [f32; 3] {
        [
            self.component(3, t),
            self.component(4, t),
            self.component(5, t),
        ]
    }
}

/// Closed uniform Catmull–Rom spline; parameter s ∈ [0, n) for n control points. Going once
/// round the loop adds `period` (non-zero for unwrapped angles).
struct Spline {
    points: Vec<Vec3>,
    period: Vec3,
}

impl Spline {
    fn new(points: Vec<Vec3>, period: Vec3) -> Self {
        Self { points, period }
    }

    fn at(&self, s: f32) -> Vec3 {
        let n = self.points.len() as i64;
        let i = s.floor() as i64;
        let t = s - i as f32;
        let p = |k: i64| {
            self.points[(i + k).rem_euclid(n) as usize] + self.period * (i + k).div_euclid(n) as f32
        };
        let (p0, p1, p2, p3) = (p(-1), p(0), p(1), p(2));
        0.5 * (2.0 * p1
            + (p2 - p0) * t
            + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t * t
            + (3.0 * p1 - p0 - 3.0 * p2 + p3) * t * t * t)
    }

    /// Cumulative arc length at s = k / SAMPLES_PER_SPAN, k = 0 ..= n·SAMPLES_PER_SPAN.
    fn arc_lengths(&self) -> Vec<f32> {
        let steps = self.points.len() * SAMPLES_PER_SPAN;
        let mut lengths = Vec::with_capacity(steps + 1);
        let mut total = 0.0;
        let mut prev = self.at(0.0);
        lengths.push(0.0);
        for k in 1..=steps {
            let p = self.at(k as f32 / SAMPLES_PER_SPAN as f32);
            total += p.distance(prev);
            lengths.push(total);
            prev = p;
        }
        lengths
    }
}

/// The spline parameter at which the cumulative length reaches `length`.
fn spline_parameter(lengths: &[f32], length: f32) -> f32 {
    let k = lengths
        .partition_point(|&l| l < length)
        .clamp(1, lengths.len() - 1);
    let (l0, l1) = (lengths[k - 1], lengths[k]);
    let frac = if l1 > l0 {
        (length - l0) / (l1 - l0)
    } else {
        0.0
    };
    (k as f32 - 1.0 + frac.clamp(0.0, 1.0)) / SAMPLES_PER_SPAN as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn track() -> Track {
        Track {
            centre: Vec2::ZERO,
            half: Vec2::new(1.5, 1.0),
            room_half: Vec2::new(3.0, 2.5),
            height: 2.7,
        }
    }

    #[test]
    fn trajectory_is_deterministic_and_has_the_replica_shape() {
        let a = default_trajectory(&track(), 42, 0.0);
        assert_eq!(a, default_trajectory(&track(), 42, 0.0));
        assert_ne!(a, default_trajectory(&track(), 43, 0.0));
        assert_eq!(a.len(), FRAMES);
        assert!((a.timestamps[1] - 0.05).abs() < 1e-12);
    }

    #[test]
    fn progress_runs_from_zero_to_one_never_backwards_and_nearly_stops() {
        let p = Progress::new(&mut Rng::new(7), 0.8);
        assert_eq!(p.at(0.0), 0.0);
        assert!((p.at(1.0) - 1.0).abs() < 1e-6);
        let steps: Vec<f32> = (0..1000)
            .map(|i| p.at((i + 1) as f32 / 1000.0) - p.at(i as f32 / 1000.0))
            .collect();
        assert!(steps.iter().all(|&d| d >= 0.0));
        let (slowest, fastest) = steps
            .iter()
            .fold((f32::MAX, 0f32), |(lo, hi), &d| (lo.min(d), hi.max(d)));
        assert!(
            fastest > 5.0 * slowest,
            "speed varies: {slowest} .. {fastest}"
        );
    }

    #[test]
    fn camera_looks_at_its_target_with_opencv_axes() {
        let eye = Vec3::new(0.0, 0.0, 1.5);
        let pose = look_pose(eye, 0.0, 0.0, 0.0);
        let forward = pose.rotation * DVec3::Z;
        let down = pose.rotation * DVec3::Y;
        let right = pose.rotation * DVec3::X;
        assert!((forward - DVec3::X).length() < 1e-9);
        assert!(
            (down + DVec3::Z).length() < 1e-9,
            "image y points down in the world"
        );
        assert!(
            (right + DVec3::Y).length() < 1e-9,
            "looking along +x, right is −y"
        );
    }

    #[test]
    fn headings_unwrap_the_short_way_and_close_the_loop() {
        let square = [Vec3::X, Vec3::Y, -Vec3::X, -Vec3::Y];
        // Each waypoint looks outward: the heading turns +90° per waypoint, once round in total.
        let angles = look_angles(&[Vec3::ZERO; 4], &square);
        let yaws: Vec<f32> = angles.iter().map(|a| a.x.to_degrees().round()).collect();
        assert_eq!(yaws, vec![0.0, 90.0, 180.0, 270.0]);
        assert_eq!(winding(&[Vec3::ZERO; 4], &square), 1.0);
        let spline = Spline::new(angles, Vec3::new(TAU, 0.0, 0.0));
        assert!(
            (spline.at(4.0).x - TAU).abs() < 1e-5,
            "continues past the seam"
        );
    }

    #[test]
    fn arc_length_parameter_inverts_the_table() {
        let spline = Spline::new(
            vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            Vec3::ZERO,
        );
        let lengths = spline.arc_lengths();
        let total = *lengths.last().unwrap();
        assert_eq!(spline_parameter(&lengths, 0.0), 0.0);
        assert!((spline_parameter(&lengths, total) - 4.0).abs() < 1e-4);
        let half = spline_parameter(&lengths, total / 2.0);
        assert!(
            (half - 2.0).abs() < 0.05,
            "symmetric loop: half the length at s = 2, got {half}"
        );
    }
}
