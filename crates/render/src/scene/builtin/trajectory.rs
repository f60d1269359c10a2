//! Default trajectories: a smooth hand-held loop around a scene's free "track", looking across the
//! room or obliquely at the walls, like the iMAP / NICE-SLAM Replica sequences.
//!
//! Waypoints sit on an ellipse inside the track (radius and height jittered per scene); the path
//! is a periodic Catmull–Rom spline through them walked once at a gently varying speed. Each
//! waypoint has a look-at target on the room's far side or along a wall; targets are splined with
//! the same parameter, and slow sinusoids add hand-held yaw, pitch, roll and position wobble.

use std::f32::consts::TAU;

use glam::{DMat3, DQuat, DVec3, Vec2, Vec3};
use rslam_core::{Pose, Trajectory};

use super::rng::Rng;

pub const FRAMES: usize = 2000;
pub const RATE_HZ: f64 = rslam_core::REPLICA_RATE_HZ;
const WAYPOINTS: usize = 10;
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
}

/// The default trajectory of a scene: `FRAMES` poses at `RATE_HZ`, deterministic in `seed`.
pub fn default_trajectory(track: &Track, seed: u64) -> Trajectory {
    let mut rng = Rng::new(seed);
    let start = rng.f32() * TAU;
    let direction = if rng.chance(0.5) { 1.0 } else { -1.0 };
    let mut points = Vec::with_capacity(WAYPOINTS);
    let mut targets = Vec::with_capacity(WAYPOINTS);
    for k in 0..WAYPOINTS {
        let a = start + direction * TAU * k as f32 / WAYPOINTS as f32;
        let radial = Vec2::new(a.cos(), a.sin());
        let r = rng.range(0.55, 1.0);
        let p = track.centre + radial * track.half * r;
        points.push(p.extend(rng.range(1.4, 1.75)));
        // Even waypoints look across the room, odd ones obliquely at the nearer walls.
        let look = if k % 2 == 0 {
            a + std::f32::consts::PI + rng.range(-0.9, 0.9)
        } else {
            a + direction * rng.range(0.9, 1.6)
        };
        targets.push(wall_target(track, p, look).extend(rng.range(0.55, 1.1)));
    }
    let path = Spline::new(points, Vec3::ZERO);
    let turns = winding(&path.points, &targets);
    let aim = Spline::new(look_angles(&path.points, &targets), Vec3::X * TAU * turns);
    let lengths = path.arc_lengths();
    let total = *lengths.last().unwrap_or(&0.0);
    let wobble = Wobble::new(&mut rng);
    let poses = (0..FRAMES)
        .map(|i| {
            let tau = i as f32 / FRAMES as f32;
            let progress = tau + 0.025 * (TAU * 3.0 * tau).sin();
            let s = spline_parameter(&lengths, progress * total);
            let t = i as f32 / RATE_HZ as f32;
            let angles = aim.at(s);
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
        }
    }

    #[test]
    fn trajectory_is_deterministic_and_has_the_replica_shape() {
        let a = default_trajectory(&track(), 42);
        assert_eq!(a, default_trajectory(&track(), 42));
        assert_ne!(a, default_trajectory(&track(), 43));
        assert_eq!(a.len(), FRAMES);
        assert!((a.timestamps[1] - 0.05).abs() < 1e-12);
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
