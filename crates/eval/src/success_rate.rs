//! SR, the success rate of tracking: how much of the ground-truth path the estimate covers.

use rslam_core::Trajectory;
use serde::Serialize;

/// SR = L_est / L_gt: the estimate's path length (every pose of the file, multiplied by the
/// Sim(3) scale when one was fitted) over the ground truth's path length between its first and
/// last timestamps (every pose of its file). An estimate that stops early gets SR < 1.
/// No reference tool computes SR; this is rslam's definition (metrics.md).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SuccessRate {
    /// `None` when the ground truth does not move.
    pub sr: Option<f64>,
    /// Metres, scaled.
    pub estimate_path: f64,
    /// Metres.
    pub ground_truth_path: f64,
}

pub fn success_rate(est: &Trajectory, gt: &Trajectory, scale: f64) -> SuccessRate {
    let estimate_path = est.path_length() * scale;
    let ground_truth_path = gt.path_length();
    SuccessRate {
        sr: (ground_truth_path > 0.0).then(|| estimate_path / ground_truth_path),
        estimate_path,
        ground_truth_path,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DQuat, DVec3};
    use rslam_core::Pose;

    fn line(lengths: &[f64]) -> Trajectory {
        let mut x = 0.0;
        let mut poses = vec![Pose::IDENTITY];
        for l in lengths {
            x += l;
            poses.push(Pose::new(DQuat::IDENTITY, DVec3::new(x, 0.0, 0.0)));
        }
        Trajectory::from_poses_at_rate(poses, 1.0)
    }

    #[test]
    fn early_stop_gives_less_than_one_and_scale_multiplies() {
        let gt = line(&[1.0, 1.0, 1.0, 1.0]);
        let est = line(&[1.0, 1.0]);
        let sr = success_rate(&est, &gt, 1.0);
        assert_eq!(sr.sr, Some(0.5));
        assert_eq!(success_rate(&est, &gt, 2.0).sr, Some(1.0));
        assert_eq!(success_rate(&est, &line(&[]), 1.0).sr, None);
    }
}
