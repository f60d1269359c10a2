//! KITTI odometry poses: one row-major 3×4 camera-to-world matrix (12 numbers) per line, no time;
//! optionally a times file with one timestamp (seconds) per line.

use std::path::Path;

use super::lines::{data_lines, LineRef};
use super::TrajectoryFormat;
use crate::{CoreError, Pose};

pub(super) fn parse(path: &Path, text: &str) -> Result<Vec<Pose>, CoreError> {
    let layout = TrajectoryFormat::Kitti.line_layout();
    data_lines(text)
        .map(|(line, content)| {
            let at = LineRef { path, line };
            let m: [f64; 12] = at.numbers(content.split_whitespace(), true, layout)?;
            at.pose_from_rows(&m)
        })
        .collect()
}

/// A KITTI `times.txt`: one timestamp in seconds per line.
pub(super) fn parse_times(path: &Path, text: &str) -> Result<Vec<f64>, CoreError> {
    data_lines(text)
        .map(|(line, content)| {
            let at = LineRef { path, line };
            let [t] = at.numbers(content.split_whitespace(), true, "1 timestamp in seconds")?;
            Ok(t)
        })
        .collect()
}
