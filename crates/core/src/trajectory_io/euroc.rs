//! EuRoC MAV ground truth (`state_groundtruth_estimate0/data.csv`): comma-separated
//! `t[ns], px, py, pz, qw, qx, qy, qz, …` (velocities and biases follow and are ignored).

use std::path::Path;

use glam::DVec3;

use super::lines::{data_lines, LineRef};
use super::TrajectoryFormat;
use crate::{CoreError, Pose, Trajectory};

const NANOSECONDS_PER_SECOND: f64 = 1e9;

pub(super) fn parse(path: &Path, text: &str) -> Result<Trajectory, CoreError> {
    let layout = TrajectoryFormat::Euroc.line_layout();
    let mut trajectory = Trajectory::default();
    for (line, content) in data_lines(text) {
        let at = LineRef { path, line };
        let [t_ns, x, y, z, qw, qx, qy, qz] =
            at.numbers(content.split(',').map(str::trim), false, layout)?;
        // As evo: the nanosecond stamp is read as a float, then divided.
        trajectory.timestamps.push(t_ns / NANOSECONDS_PER_SECOND);
        trajectory.poses.push(Pose::new(
            at.quaternion(qx, qy, qz, qw)?,
            DVec3::new(x, y, z),
        ));
    }
    Ok(trajectory)
}
