//! Test support: a smooth hand-held-like camera walk, in closed form.

use glam::{DQuat, DVec3, EulerRot};

use crate::{Pose, Trajectory};

/// Pose rate of rslam's built-in scenes (Replica's rate).
pub const POSE_RATE_HZ: f64 = crate::REPLICA_RATE_HZ;

/// The walk's `world_from_body` at `t` seconds: round an ellipse at 0.2–0.4 m/s with a little
/// bob and sway, yawing at up to about 27°/s while pitching and rolling gently (world z up).
pub fn hand_held_pose(t: f64) -> Pose {
    let position = DVec3::new(
        1.5 * (0.2 * t).cos() + 0.03 * (2.1 * t).sin(),
        1.0 * (0.2 * t).sin() + 0.03 * (1.7 * t).cos(),
        1.5 + 0.05 * (1.3 * t).sin(),
    );
    let yaw = 0.2 * t + 0.3 * (0.9 * t).sin();
    let pitch = 0.15 * (0.7 * t).sin();
    let roll = 0.05 * (1.1 * t + 0.4).sin();
    Pose::new(DQuat::from_euler(EulerRot::ZYX, yaw, pitch, roll), position)
}

/// `seconds` of the walk sampled at [`POSE_RATE_HZ`], starting at `start` seconds.
pub fn hand_held_trajectory(start: f64, seconds: f64) -> Trajectory {
    let count = (seconds * POSE_RATE_HZ).round() as usize + 1;
    let timestamps: Vec<f64> = (0..count)
        .map(|i| start + i as f64 / POSE_RATE_HZ)
        .collect();
    let poses = timestamps.iter().map(|&t| hand_held_pose(t)).collect();
    Trajectory::new(timestamps, poses)
}

/// The angle between two orientations, accurate near zero (unlike an arc cosine of their dot).
pub fn rotation_angle(a: DQuat, b: DQuat) -> f64 {
    let d = a.inverse() * b;
    2.0 * d.xyz().length().atan2(d.w.abs())
}
