//! Replica `traj.txt`: one row-major 4×4 camera-to-world matrix (16 numbers) per line.

use std::fmt::Write as _;
use std::path::Path;

use super::lines::{data_lines, LineRef};
use super::TrajectoryFormat;
use crate::{CoreError, Trajectory};

pub(super) fn parse(path: &Path, text: &str, rate_hz: f64) -> Result<Trajectory, CoreError> {
    let layout = TrajectoryFormat::Replica.line_layout();
    let mut poses = Vec::new();
    for (line, content) in data_lines(text) {
        let at = LineRef { path, line };
        let m: [f64; 16] = at.numbers(content.split_whitespace(), true, layout)?;
        poses.push(at.pose_from_rows(&m)?);
    }
    Ok(Trajectory::from_poses_at_rate(poses, rate_hz))
}

/// Writes `traj` as a Replica `traj.txt`: 16 numbers per line, row-major 4×4 camera-to-world,
/// each with 18 significant digits so the matrices read back bit for bit. Timestamps are not
/// stored (the format has none).
pub fn write_replica(path: &Path, traj: &Trajectory) -> Result<(), CoreError> {
    let mut text = String::with_capacity(16 * 26 * traj.len());
    for pose in &traj.poses {
        let row: Vec<String> = pose
            .to_row_major()
            .iter()
            .map(|v| format!("{v:.17e}"))
            .collect();
        // Writing to a String cannot fail.
        let _ = writeln!(text, "{}", row.join(" "));
    }
    std::fs::write(path, text).map_err(|e| CoreError::io(path, e))
}
