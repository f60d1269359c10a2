//! Trajectory files, format detected from the content (TUM, Replica, KITTI, EuRoC).

use rslam_core::limits::MAX_POSES;
use rslam_core::trajectory_io::read_trajectory;

use crate::Scratch;

pub const FILE: &str = "trajectory.txt";

/// Largest deviation of an accepted rotation quaternion's length from 1.
const UNIT_TOLERANCE: f64 = 1e-9;

/// An accepted trajectory holds only finite times and rigid poses: no NaN slips through.
pub fn check(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    let path = scratch.write(FILE, input)?;
    let file = read_trajectory(&path, None).map_err(|e| e.to_string())?;
    let trajectory = &file.trajectory;
    assert!(
        !trajectory.is_empty() && trajectory.len() <= MAX_POSES,
        "accepted {} poses",
        trajectory.len()
    );
    assert_eq!(trajectory.timestamps.len(), trajectory.len());
    for (i, (t, pose)) in trajectory
        .timestamps
        .iter()
        .zip(&trajectory.poses)
        .enumerate()
    {
        assert!(t.is_finite(), "pose {i}: accepted timestamp {t}");
        assert!(
            pose.translation.is_finite(),
            "pose {i}: accepted translation {}",
            pose.translation
        );
        assert!(
            pose.rotation.is_finite() && (pose.rotation.length() - 1.0).abs() < UNIT_TOLERANCE,
            "pose {i}: accepted rotation {}",
            pose.rotation
        );
    }
    Ok(())
}
