//! Pairs estimate poses with ground-truth poses, exactly as evo 1.38.1
//! (`evo.core.sync.associate_trajectories` with the default `nearest_time` method).

use rslam_core::{nearest_time, Trajectory};
use serde::Serialize;

use crate::EvalError;

/// evo's default `--t_max_diff`.
pub const DEFAULT_MAX_DIFF: f64 = 0.01;

/// How estimate and ground-truth poses are paired.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "by")]
pub enum Matching {
    /// Nearest timestamp within `max_diff` seconds (inclusive); `t_offset` is added to the
    /// estimate's timestamps.
    Time { max_diff: f64, t_offset: f64 },
    /// Pose `i` with pose `i`, for trajectories without timestamps (KITTI).
    Index,
}

impl Default for Matching {
    fn default() -> Self {
        Matching::Time {
            max_diff: DEFAULT_MAX_DIFF,
            t_offset: 0.0,
        }
    }
}

/// Index pairs into the estimate and the ground truth, in the order of the trajectory that has
/// fewer poses.
#[derive(Clone, Debug, PartialEq)]
pub struct Association {
    pub est_indices: Vec<usize>,
    pub gt_indices: Vec<usize>,
    /// The most pairs there could be: the pose count of the shorter trajectory.
    pub max_pairs: usize,
}

impl Association {
    pub fn len(&self) -> usize {
        self.est_indices.len()
    }

    pub fn is_empty(&self) -> bool {
        self.est_indices.is_empty()
    }
}

/// Associates `est` with `gt`. By time: every pose of the trajectory with fewer poses (the
/// estimate on a tie) takes the pose of the other with the nearest timestamp, kept if
/// |Δt| ≤ max_diff; not one-to-one. Zero pairs is an error showing both time ranges.
pub fn associate(
    est: &Trajectory,
    gt: &Trajectory,
    matching: &Matching,
) -> Result<Association, EvalError> {
    for (trajectory, which) in [(est, "estimate"), (gt, "ground truth")] {
        if trajectory.is_empty() {
            return Err(EvalError::EmptyTrajectory { which });
        }
    }
    let (max_diff, t_offset) = match *matching {
        Matching::Index => return Ok(associate_by_index(est, gt)),
        Matching::Time { max_diff, t_offset } => (max_diff, t_offset),
    };
    if !(max_diff.is_finite() && max_diff >= 0.0) {
        return Err(EvalError::BadOption {
            name: "max-diff",
            value: max_diff.to_string(),
            expected: "a finite number of seconds >= 0",
        });
    }
    if !t_offset.is_finite() {
        return Err(EvalError::BadOption {
            name: "t-offset",
            value: t_offset.to_string(),
            expected: "a finite number of seconds",
        });
    }
    // evo: traj_1 = reference, traj_2 = estimate (offset_2 applies to it); start from the one
    // with fewer poses, the estimate on a tie.
    let est_longer = est.len() > gt.len();
    let association = if est_longer {
        let (gt_idx, est_idx) =
            matching_time_indices(&gt.timestamps, &est.timestamps, max_diff, t_offset);
        Association {
            est_indices: est_idx,
            gt_indices: gt_idx,
            max_pairs: gt.len(),
        }
    } else {
        let (est_idx, gt_idx) =
            matching_time_indices(&est.timestamps, &gt.timestamps, max_diff, -t_offset);
        Association {
            est_indices: est_idx,
            gt_indices: gt_idx,
            max_pairs: est.len(),
        }
    };
    if association.is_empty() {
        return Err(no_matches(est, gt, max_diff, t_offset));
    }
    Ok(association)
}

/// The ground-truth poses the estimate tracks: by time, those with an estimate pose within
/// `max_diff` (after `t_offset`), each ground-truth pose looking for its nearest estimate pose
/// whichever trajectory is longer, so that 100 Hz motion capture against a 30 Hz estimate counts
/// every covered pose; by index, the first min(n) poses. Ascending.
pub fn tracked_ground_truth(est: &Trajectory, gt: &Trajectory, matching: &Matching) -> Vec<usize> {
    match *matching {
        Matching::Index => (0..est.len().min(gt.len())).collect(),
        Matching::Time { max_diff, t_offset } => {
            matching_time_indices(&gt.timestamps, &est.timestamps, max_diff, t_offset).0
        }
    }
}

fn associate_by_index(est: &Trajectory, gt: &Trajectory) -> Association {
    let n = est.len().min(gt.len());
    Association {
        est_indices: (0..n).collect(),
        gt_indices: (0..n).collect(),
        max_pairs: n,
    }
}

/// evo's `matching_time_indices`: for each stamp of `stamps_1`, the index of the nearest stamp of
/// `stamps_2 + offset_2`. Binary search when `stamps_2` is sorted, linear search otherwise.
fn matching_time_indices(
    stamps_1: &[f64],
    stamps_2: &[f64],
    max_diff: f64,
    offset_2: f64,
) -> (Vec<usize>, Vec<usize>) {
    let stamps_2: Vec<f64> = stamps_2.iter().map(|t| t + offset_2).collect();
    let mut indices_1 = Vec::with_capacity(stamps_1.len());
    let mut indices_2 = Vec::with_capacity(stamps_1.len());
    let (Some(&first), Some(&last)) = (stamps_2.first(), stamps_2.last()) else {
        return (indices_1, indices_2);
    };
    let sorted = stamps_2.windows(2).all(|w| w[1] >= w[0]);
    for (index_1, &stamp_1) in stamps_1.iter().enumerate() {
        let best = if sorted {
            if stamp_1 < first - max_diff || stamp_1 > last + max_diff {
                continue;
            }
            nearest_in_sorted(&stamps_2, stamp_1, max_diff)
        } else {
            nearest_time(stamps_2.iter().copied(), stamp_1, max_diff)
        };
        if let Some(index_2) = best {
            indices_1.push(index_1);
            indices_2.push(index_2);
        }
    }
    (indices_1, indices_2)
}

/// The branch of evo's search for sorted stamps, with its tie-breaking: `searchsorted(side =
/// "right")`, the upper neighbour only when strictly closer.
fn nearest_in_sorted(stamps: &[f64], stamp: f64, max_diff: f64) -> Option<usize> {
    let upper = stamps
        .partition_point(|&t| t <= stamp)
        .min(stamps.len() - 1);
    let diff_upper = stamps[upper] - stamp;
    let diff_lower = if upper > 0 {
        stamp - stamps[upper - 1]
    } else {
        f64::INFINITY
    };
    if diff_upper <= max_diff && diff_upper < diff_lower {
        Some(upper)
    } else if diff_lower <= max_diff && diff_lower <= diff_upper {
        Some(upper - 1)
    } else {
        None
    }
}

fn no_matches(est: &Trajectory, gt: &Trajectory, max_diff: f64, t_offset: f64) -> EvalError {
    let range = |t: &Trajectory| {
        let lo = t.timestamps.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = t
            .timestamps
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        (lo, hi)
    };
    let (est_start, est_end) = range(est);
    let (gt_start, gt_end) = range(gt);
    let est_scale = est_start.abs().max(est_end.abs());
    let gt_scale = gt_start.abs().max(gt_end.abs());
    // Nanosecond stamps are ~1e9 times second stamps of the same clock.
    let ratio = est_scale.max(gt_scale) / est_scale.min(gt_scale).max(f64::MIN_POSITIVE);
    let hint = if (1e6..1e12).contains(&ratio) {
        " (one file looks like nanoseconds, the other like seconds)"
    } else {
        ""
    };
    EvalError::NoMatches {
        max_diff,
        t_offset,
        est_start: est_start + t_offset,
        est_end: est_end + t_offset,
        gt_start,
        gt_end,
        hint,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rslam_core::Pose;

    fn stamped(stamps: &[f64]) -> Trajectory {
        Trajectory::new(stamps.to_vec(), vec![Pose::IDENTITY; stamps.len()])
    }

    fn time(max_diff: f64, t_offset: f64) -> Matching {
        Matching::Time { max_diff, t_offset }
    }

    #[test]
    fn shorter_trajectory_picks_nearest_partners_not_one_to_one() {
        let est = stamped(&[1.0, 1.004, 2.0]);
        let gt = stamped(&[0.99, 1.001, 1.5, 2.02, 2.5]);
        let a = associate(&est, &gt, &time(0.01, 0.0)).unwrap();
        // 1.0 and 1.004 both pick 1.001; 2.0 is 0.02 from 2.02 and dropped.
        assert_eq!(a.est_indices, vec![0, 1]);
        assert_eq!(a.gt_indices, vec![1, 1]);
        assert_eq!(a.max_pairs, 3);
    }

    #[test]
    fn max_diff_is_inclusive_and_ties_go_to_the_lower_stamp() {
        // Exactly representable stamps so that |Δt| == max_diff holds in floating point.
        let est = stamped(&[1.0, 3.0]);
        let gt = stamped(&[0.75, 1.25, 2.0, 2.5, 3.25, 4.0]);
        let a = associate(&est, &gt, &time(0.25, 0.0)).unwrap();
        assert_eq!(a.est_indices, vec![0, 1]);
        assert_eq!(a.gt_indices, vec![0, 4]);
    }

    #[test]
    fn duplicate_stamps_resolve_to_the_last_of_them_as_in_evo() {
        let est = stamped(&[1.0]);
        let gt = stamped(&[0.5, 1.0, 1.0, 1.5]);
        let a = associate(&est, &gt, &time(0.01, 0.0)).unwrap();
        assert_eq!(a.gt_indices, vec![2]);
    }

    #[test]
    fn longer_estimate_is_the_one_searched_and_offset_shifts_it() {
        let est = stamped(&[10.0, 10.1, 10.2, 10.3]);
        let gt = stamped(&[0.1, 0.3]);
        let a = associate(&est, &gt, &time(0.01, -10.0)).unwrap();
        assert_eq!(a.gt_indices, vec![0, 1]);
        assert_eq!(a.est_indices, vec![1, 3]);
        assert_eq!(a.max_pairs, 2);
        // The same with the shorter trajectory being the estimate.
        let a = associate(&gt, &est, &time(0.01, 10.0)).unwrap();
        assert_eq!(a.est_indices, vec![0, 1]);
        assert_eq!(a.gt_indices, vec![1, 3]);
    }

    #[test]
    fn unsorted_stamps_use_the_linear_search() {
        let est = stamped(&[2.0, 1.0]);
        let gt = stamped(&[3.0, 1.001, 2.002, 0.0]);
        let a = associate(&est, &gt, &time(0.01, 0.0)).unwrap();
        assert_eq!(a.gt_indices, vec![2, 1]);
    }

    #[test]
    fn no_match_error_shows_both_ranges_and_the_unit_hint() {
        let est = stamped(&[1.3e18, 1.4e18]);
        let gt = stamped(&[1.3e9, 1.4e9]);
        let err = associate(&est, &gt, &Matching::default())
            .unwrap_err()
            .to_string();
        assert_eq!(
            err,
            "no matching timestamps: no estimate pose lies within 0.01 s of a ground-truth pose \
             (t-offset 0 s); the estimate spans 1300000000000000000.000000 .. \
             1400000000000000000.000000 s, the ground truth 1300000000.000000 .. 1400000000.000000 s \
             (one file looks like nanoseconds, the other like seconds)"
        );
        let off = stamped(&[5.0, 6.0]);
        let err = associate(&off, &stamped(&[1.0, 2.0]), &Matching::default()).unwrap_err();
        assert!(
            err.to_string()
                .ends_with("the ground truth 1.000000 .. 2.000000 s"),
            "{err}"
        );
    }

    #[test]
    fn index_matching_pairs_the_common_prefix() {
        let a = associate(
            &stamped(&[0.0, 1.0, 2.0]),
            &stamped(&[0.0, 1.0]),
            &Matching::Index,
        )
        .unwrap();
        assert_eq!(a.est_indices, vec![0, 1]);
        assert_eq!(a.gt_indices, vec![0, 1]);
    }

    #[test]
    fn empty_trajectories_are_errors_in_both_modes() {
        let some = stamped(&[0.0]);
        let none = stamped(&[]);
        for matching in [Matching::default(), Matching::Index] {
            let err = associate(&none, &some, &matching).unwrap_err();
            assert_eq!(err.to_string(), "the estimate has no poses");
            let err = associate(&some, &none, &matching).unwrap_err();
            assert_eq!(err.to_string(), "the ground truth has no poses");
        }
    }

    #[test]
    fn negative_max_diff_is_rejected() {
        let t = stamped(&[0.0]);
        let err = associate(&t, &t, &time(-1.0, 0.0)).unwrap_err();
        assert_eq!(
            err.to_string(),
            "max-diff = -1: expected a finite number of seconds >= 0"
        );
    }
}
