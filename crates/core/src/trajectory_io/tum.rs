//! TUM RGB-D trajectories: `t tx ty tz qx qy qz qw` per line, `#` comments.

use std::fmt::Write as _;
use std::path::Path;

use glam::DVec3;

use super::lines::{data_lines, LineRef};
use super::TrajectoryFormat;
use crate::{CoreError, Pose, Trajectory};

pub(super) fn parse(path: &Path, text: &str) -> Result<Trajectory, CoreError> {
    let layout = TrajectoryFormat::Tum.line_layout();
    let mut trajectory = Trajectory::default();
    for (line, content) in data_lines(text) {
        let at = LineRef { path, line };
        let [t, x, y, z, qx, qy, qz, qw] = at.numbers(content.split_whitespace(), true, layout)?;
        trajectory.timestamps.push(t);
        trajectory.poses.push(Pose::new(
            at.quaternion(qx, qy, qz, qw)?,
            DVec3::new(x, y, z),
        ));
    }
    Ok(trajectory)
}

/// Writes `traj` as a TUM `groundtruth.txt`: three `#` header lines, then
/// `t tx ty tz qx qy qz qw` with 6-decimal timestamps and shortest round-trip numbers.
pub fn write_tum(path: &Path, traj: &Trajectory) -> Result<(), CoreError> {
    let mut text = String::with_capacity(64 * (traj.len() + 3));
    text.push_str("# ground truth trajectory\n");
    text.push_str("# written by rslam\n");
    text.push_str("# timestamp tx ty tz qx qy qz qw\n");
    for (t, pose) in traj.timestamps.iter().zip(&traj.poses) {
        let p = pose.translation;
        let q = pose.rotation;
        // Writing to a String cannot fail.
        let _ = writeln!(
            text,
            "{t:.6} {} {} {} {} {} {} {}",
            p.x, p.y, p.z, q.x, q.y, q.z, q.w
        );
    }
    std::fs::write(path, text).map_err(|e| CoreError::io(path, e))
}
