//! EuRoC MAV ground truth (`state_groundtruth_estimate0/data.csv`): comma-separated
//! `t[ns], px, py, pz, qw, qx, qy, qz, …` (velocities and biases follow and are ignored here).
//! The column split and the pose columns are shared with the EuRoC dataset reader
//! (`dataset::euroc`), which reads every column.

use std::path::Path;

use glam::DVec3;

use super::lines::{data_lines, LineRef};
use super::TrajectoryFormat;
use crate::{CoreError, Pose, Trajectory};

const NANOSECONDS_PER_SECOND: f64 = 1e9;

/// The fields of one EuRoC CSV line, blanks around each trimmed (the published ground-truth
/// header has a blank after each comma, the data lines none).
pub(crate) fn fields(content: &str) -> impl Iterator<Item = &str> {
    content.split(',').map(str::trim)
}

/// The body pose from ground-truth columns 2–8: `p_RS_R` x y z, then `q_RS` **w** x y z.
pub(crate) fn pose_from_columns(
    at: &LineRef,
    [x, y, z, qw, qx, qy, qz]: [f64; 7],
) -> Result<Pose, CoreError> {
    Ok(Pose::new(
        at.quaternion(qx, qy, qz, qw)?,
        DVec3::new(x, y, z),
    ))
}

pub(super) fn parse(path: &Path, text: &str) -> Result<Trajectory, CoreError> {
    let layout = TrajectoryFormat::Euroc.line_layout();
    let mut trajectory = Trajectory::default();
    for (line, content) in data_lines(text) {
        let at = LineRef { path, line };
        let [t_ns, x, y, z, qw, qx, qy, qz] = at.numbers(fields(content), false, layout)?;
        // As evo: the nanosecond stamp is read as a float, then divided.
        trajectory.timestamps.push(t_ns / NANOSECONDS_PER_SECOND);
        trajectory
            .poses
            .push(pose_from_columns(&at, [x, y, z, qw, qx, qy, qz])?);
    }
    Ok(trajectory)
}
