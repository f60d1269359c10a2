//! SR, the success rate of tracking: how much of the ground-truth path the estimate covers; beside
//! it the paper's literal formula (a path-length ratio) and the fraction of frames tracked.

use rslam_core::Trajectory;
use serde::Serialize;

use crate::association::{tracked_ground_truth, Matching};

/// How much of the ground truth the estimate tracks (docs/src/metrics.md, "SR (success rate of tracking)"). No reference tool
/// computes these; they are rslam's definitions.
///
/// The evaluated span is the whole ground truth, every pose of its file: an estimate that starts
/// late or stops early is not forgiven the part it missed. A ground-truth pose is *tracked* when
/// an estimate pose lies within `max_diff` of it (the matching ATE uses, but from every
/// ground-truth pose: a ground truth recorded faster than the estimate is covered too).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SuccessRate {
    /// Covered over whole ground-truth path, in [0, 1]: a segment between consecutive
    /// ground-truth poses is covered when both its ends are tracked. Scale-free, and jitter does
    /// not change it; a lost tracker that keeps reporting a pose still covers (ATE shows it).
    /// `None` when the ground truth does not move.
    pub sr: Option<f64>,
    /// The paper's literal SR, L_est / L_gt: the estimate's path length (scaled) over the ground
    /// truth's. Jitter adds path length, so it can exceed 1. `None` when the ground truth does
    /// not move.
    pub sr_path_ratio: Option<f64>,
    /// Tracked ground-truth poses over all ground-truth poses, in [0, 1].
    pub tracked_fraction: f64,
    pub tracked_poses: usize,
    pub ground_truth_poses: usize,
    pub path_length: PathLengths,
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PathLengths {
    /// The estimate's (every pose of its file, times the Sim(3) scale when one was fitted), m.
    pub estimate: f64,
    /// The ground truth's (every pose of its file), metres.
    pub ground_truth: f64,
    /// The ground truth's covered segments, metres.
    pub covered: f64,
}

/// `matching` pairs `est` with `gt` as for ATE; `scale` is the fitted Sim(3) scale (1 otherwise)
/// and only enters `sr_path_ratio`.
pub fn success_rate(
    est: &Trajectory,
    gt: &Trajectory,
    matching: &Matching,
    scale: f64,
) -> SuccessRate {
    let mut tracked = vec![false; gt.len()];
    for i in tracked_ground_truth(est, gt, matching) {
        tracked[i] = true;
    }
    let tracked_poses = tracked.iter().filter(|&&t| t).count();
    let mut ground_truth_path = 0.0;
    let mut covered = 0.0;
    for (poses, ends) in gt.poses.windows(2).zip(tracked.windows(2)) {
        let length = (poses[1].translation - poses[0].translation).length();
        ground_truth_path += length;
        if ends[0] && ends[1] {
            covered += length;
        }
    }
    let estimate_path = est.path_length() * scale;
    let moves = ground_truth_path > 0.0;
    SuccessRate {
        sr: moves.then(|| covered / ground_truth_path),
        sr_path_ratio: moves.then(|| estimate_path / ground_truth_path),
        tracked_fraction: tracked_poses as f64 / gt.len().max(1) as f64,
        tracked_poses,
        ground_truth_poses: gt.len(),
        path_length: PathLengths {
            estimate: estimate_path,
            ground_truth: ground_truth_path,
            covered,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::association::Matching;
    use glam::{DQuat, DVec3};
    use rslam_core::Pose;

    /// Rounding of sums of a hundred lengths of about a metre.
    const SUM_TOL: f64 = 1e-12;
    const RATE_HZ: f64 = 30.0;

    /// Poses on the x axis at `x(i)`, 30 Hz.
    fn along_x(n: usize, x: impl Fn(f64) -> f64) -> Trajectory {
        let poses = (0..n)
            .map(|i| Pose::new(DQuat::IDENTITY, DVec3::new(x(i as f64), 0.0, 0.0)))
            .collect();
        Trajectory::from_poses_at_rate(poses, RATE_HZ)
    }

    fn keep(t: &Trajectory, keep: impl Fn(usize) -> bool) -> Trajectory {
        let (timestamps, poses) = (0..t.len())
            .filter(|&i| keep(i))
            .map(|i| (t.timestamps[i], t.poses[i]))
            .unzip();
        Trajectory::new(timestamps, poses)
    }

    fn of(est: &Trajectory, gt: &Trajectory, scale: f64) -> SuccessRate {
        success_rate(est, gt, &Matching::default(), scale)
    }

    #[test]
    fn first_half_only_covers_half_the_path_less_the_straddling_segment() {
        // 100 poses 1 cm apart: 99 segments; the first 50 poses span 49 of them.
        let gt = along_x(100, |i| 0.01 * i);
        let sr = of(&keep(&gt, |i| i < 50), &gt, 1.0);
        assert!((sr.sr.unwrap() - 49.0 / 99.0).abs() < SUM_TOL);
        assert_eq!((sr.tracked_poses, sr.ground_truth_poses), (50, 100));
        assert_eq!(sr.tracked_fraction, 0.5);
    }

    #[test]
    fn the_span_is_the_whole_ground_truth_so_a_late_start_is_not_forgiven() {
        let gt = along_x(100, |i| 0.01 * i);
        let sr = of(&keep(&gt, |i| i >= 50), &gt, 1.0);
        assert!((sr.sr.unwrap() - 49.0 / 99.0).abs() < SUM_TOL);
        assert_eq!(sr.tracked_fraction, 0.5);
    }

    #[test]
    fn a_gap_loses_exactly_the_path_from_the_pose_before_it_to_the_pose_after_it() {
        // x = i²/1000: segment i → i+1 is (2i + 1)/1000 long, so each segment counts differently.
        let gt = along_x(100, |i| 0.001 * i * i);
        let sr = of(&keep(&gt, |i| !(40..60).contains(&i)), &gt, 1.0);
        let total = 0.001 * 99.0 * 99.0;
        let gap = 0.001 * (60.0 * 60.0 - 39.0 * 39.0);
        assert!((sr.path_length.ground_truth - total).abs() < SUM_TOL);
        assert!((sr.path_length.covered - (total - gap)).abs() < SUM_TOL);
        assert!((sr.sr.unwrap() - (total - gap) / total).abs() < SUM_TOL);
        assert_eq!(sr.tracked_fraction, 0.8);
    }

    #[test]
    fn a_denser_estimate_tracks_every_ground_truth_pose_once() {
        let gt = along_x(100, |i| 0.01 * i);
        // 60 Hz over the same span: twice the poses, yet at most every ground-truth pose.
        let dense = Trajectory::from_poses_at_rate(along_x(199, |i| 0.005 * i).poses, 60.0);
        let sr = of(&dense, &gt, 1.0);
        assert_eq!(sr.tracked_fraction, 1.0);
        assert_eq!(sr.sr, Some(1.0));
    }

    #[test]
    fn a_sparser_estimate_covers_the_denser_ground_truth_it_spans() {
        // 100 Hz motion capture against a 30 Hz camera (TUM): every ground-truth pose has an
        // estimate pose within 1/60 s, inside a max_diff of 0.02 s.
        let gt = Trajectory::from_poses_at_rate(along_x(301, |i| 0.001 * i).poses, 100.0);
        let camera = Trajectory::from_poses_at_rate(along_x(91, |i| 0.01 / 3.0 * i).poses, 30.0);
        let matching = Matching::Time {
            max_diff: 0.02,
            t_offset: 0.0,
        };
        let full = success_rate(&camera, &gt, &matching, 1.0);
        assert_eq!(full.sr, Some(1.0));
        assert_eq!(full.tracked_fraction, 1.0);
        let first_third = keep(&camera, |i| i <= 30);
        let part = success_rate(&first_third, &gt, &matching, 1.0);
        // Camera poses up to t = 1 s track ground truth up to t = 1.02 s: 102 of 300 segments.
        assert!(
            (part.sr.unwrap() - 102.0 / 300.0).abs() < SUM_TOL,
            "{part:?}"
        );
    }

    #[test]
    fn scale_multiplies_the_path_ratio_only() {
        let gt = along_x(100, |i| 0.01 * i);
        let half = keep(&gt, |i| i < 50);
        let unscaled = of(&half, &gt, 1.0);
        let scaled = of(&half, &gt, 2.0);
        assert_eq!(scaled.sr, unscaled.sr);
        let ratio = unscaled.sr_path_ratio.unwrap();
        assert!((ratio - 49.0 / 99.0).abs() < SUM_TOL);
        assert!((scaled.sr_path_ratio.unwrap() - 2.0 * ratio).abs() < SUM_TOL);
    }

    #[test]
    fn a_still_ground_truth_has_no_sr() {
        let still = along_x(10, |_| 0.0);
        let sr = of(&still, &still, 1.0);
        assert_eq!((sr.sr, sr.sr_path_ratio), (None, None));
        assert_eq!(sr.tracked_fraction, 1.0);
    }
}
