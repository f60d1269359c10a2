//! RPE pair selection, exactly as evo 1.38.1 (`filters.filter_pairs_by_index`, `_by_path`,
//! `_by_angle`, with `metrics.id_pairs_from_delta`'s relative tolerance of 10 %).

use rslam_core::Pose;

use crate::rpe::{rotation_angle, DeltaUnit, RpeOptions};
use crate::EvalError;

/// evo's `rel_delta_tol`: in all-pairs mode a pair is kept when its path length or angle is
/// within 10 % of delta.
const RELATIVE_DELTA_TOLERANCE: f64 = 0.1;

/// Index pairs (i, j), i < j, into `poses` for the given delta.
pub fn pose_pairs(poses: &[Pose], options: &RpeOptions) -> Result<Vec<(usize, usize)>, EvalError> {
    let delta = options.delta;
    let tolerance = delta * RELATIVE_DELTA_TOLERANCE;
    let pairs = match options.delta_unit {
        DeltaUnit::Frames => {
            if !(delta >= 1.0 && delta.fract() == 0.0 && delta <= usize::MAX as f64) {
                return Err(bad_delta(delta, "a whole number of frames >= 1"));
            }
            by_index(poses.len(), delta as usize, options.all_pairs)
        }
        DeltaUnit::Meters => {
            if !(delta.is_finite() && delta > 0.0) {
                return Err(bad_delta(delta, "a distance in metres > 0"));
            }
            let positions: Vec<_> = poses.iter().map(|p| p.translation).collect();
            if options.all_pairs {
                by_path_all(&positions, delta, tolerance)
            } else {
                by_path_consecutive(&positions, delta)
            }
        }
        DeltaUnit::Degrees => {
            if !(delta > 0.0 && delta <= 180.0) {
                return Err(bad_delta(delta, "an angle in degrees in (0, 180]"));
            }
            let (delta, tolerance) = (delta.to_radians(), tolerance.to_radians());
            if options.all_pairs {
                by_angle_all(poses, delta, tolerance)
            } else {
                by_angle_consecutive(poses, delta)
            }
        }
    };
    if pairs.is_empty() {
        return Err(EvalError::NoRpePairs {
            delta,
            unit: options.delta_unit.long_name(),
            poses: poses.len(),
        });
    }
    Ok(pairs)
}

fn bad_delta(delta: f64, expected: &'static str) -> EvalError {
    EvalError::BadOption {
        name: "delta",
        value: delta.to_string(),
        expected,
    }
}

fn by_index(n: usize, delta: usize, all_pairs: bool) -> Vec<(usize, usize)> {
    if all_pairs {
        (0..n.saturating_sub(delta))
            .map(|i| (i, i + delta))
            .collect()
    } else {
        let starts: Vec<usize> = (0..n).step_by(delta).collect();
        starts.windows(2).map(|w| (w[0], w[1])).collect()
    }
}

/// Consecutive pairs: a new pair end wherever the path since the last end reaches delta; index 0
/// always starts the first pair (evo ≥ 1.37).
fn by_path_consecutive(positions: &[glam::DVec3], delta: f64) -> Vec<(usize, usize)> {
    let mut ends = vec![0];
    let mut path = 0.0;
    for (i, w) in positions.windows(2).enumerate() {
        path += (w[1] - w[0]).length();
        if path >= delta {
            ends.push(i + 1);
            path = 0.0;
        }
    }
    ends.windows(2).map(|w| (w[0], w[1])).collect()
}

/// For every start i, the end j > i whose path distance from i is nearest delta (the first such
/// j, as numpy's argmin), kept within the tolerance. evo scans all j; the accumulated distances
/// are sorted, so a binary search finds the same j.
fn by_path_all(positions: &[glam::DVec3], delta: f64, tolerance: f64) -> Vec<(usize, usize)> {
    let mut accumulated = Vec::with_capacity(positions.len());
    let mut total = 0.0;
    accumulated.push(total);
    for w in positions.windows(2) {
        total += (w[1] - w[0]).length();
        accumulated.push(total);
    }
    let n = accumulated.len();
    let mut pairs = Vec::new();
    for i in 0..n.saturating_sub(1) {
        let base = accumulated[i];
        let from_here = |j: usize| accumulated[j] - base;
        // First j with from_here(j) >= value; `from_here` is non-decreasing in j.
        let first_at_least =
            |value: f64| i + 1 + accumulated[i + 1..].partition_point(|&a| a - base < value);
        let k = first_at_least(delta);
        let candidate = if k == n {
            first_at_least(from_here(n - 1))
        } else if k == i + 1 {
            k
        } else {
            let below = (from_here(k - 1) - delta).abs();
            let above = (from_here(k) - delta).abs();
            if below <= above {
                first_at_least(from_here(k - 1))
            } else {
                k
            }
        };
        if (from_here(candidate) - delta).abs() <= tolerance {
            pairs.push((i, candidate));
        }
    }
    pairs
}

/// Consecutive pairs: a pair ends wherever the rotation accumulated since its start reaches delta.
fn by_angle_consecutive(poses: &[Pose], delta: f64) -> Vec<(usize, usize)> {
    let mut pairs = Vec::new();
    let mut accumulated = 0.0;
    let mut start = 0;
    for (i, w) in poses.windows(2).enumerate() {
        accumulated += rotation_angle(w[0].rotation.inverse() * w[1].rotation);
        if accumulated >= delta {
            pairs.push((start, i + 1));
            accumulated = 0.0;
            start = i + 1;
        }
    }
    pairs
}

/// Every pair (i, j > i) whose direct relative angle lies in [delta − tol, delta + tol].
/// Quadratic, as in evo.
fn by_angle_all(poses: &[Pose], delta: f64, tolerance: f64) -> Vec<(usize, usize)> {
    let (lower, upper) = (delta - tolerance, delta + tolerance);
    let mut pairs = Vec::new();
    for (i, pi) in poses.iter().enumerate() {
        let inverse = pi.rotation.inverse();
        for (j, pj) in poses.iter().enumerate().skip(i + 1) {
            let angle = rotation_angle(inverse * pj.rotation);
            if (lower..=upper).contains(&angle) {
                pairs.push((i, j));
            }
        }
    }
    pairs
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DQuat, DVec3};

    fn options(delta: f64, delta_unit: DeltaUnit, all_pairs: bool) -> RpeOptions {
        RpeOptions {
            delta,
            delta_unit,
            all_pairs,
        }
    }

    fn along_x(steps: &[f64]) -> Vec<Pose> {
        let mut x = 0.0;
        let mut poses = vec![Pose::IDENTITY];
        for s in steps {
            x += s;
            poses.push(Pose::new(DQuat::IDENTITY, DVec3::X * x));
        }
        poses
    }

    fn turning(steps_deg: &[f64]) -> Vec<Pose> {
        let mut a: f64 = 0.0;
        let mut poses = vec![Pose::IDENTITY];
        for s in steps_deg {
            a += s;
            poses.push(Pose::new(
                DQuat::from_rotation_z(a.to_radians()),
                DVec3::ZERO,
            ));
        }
        poses
    }

    #[test]
    fn frame_pairs_consecutive_and_all() {
        let poses = vec![Pose::IDENTITY; 7];
        let consecutive = pose_pairs(&poses, &options(3.0, DeltaUnit::Frames, false)).unwrap();
        assert_eq!(consecutive, vec![(0, 3), (3, 6)]);
        let all = pose_pairs(&poses, &options(3.0, DeltaUnit::Frames, true)).unwrap();
        assert_eq!(all, vec![(0, 3), (1, 4), (2, 5), (3, 6)]);
    }

    #[test]
    fn path_pairs_consecutive_restart_the_count_at_each_end() {
        let poses = along_x(&[0.5, 0.25, 0.5, 1.0, 0.5, 0.25]);
        let pairs = pose_pairs(&poses, &options(1.0, DeltaUnit::Meters, false)).unwrap();
        // Path 0.5, 0.75, 1.25 → end at 3; then 1.0 → end at 4; then 0.5, 0.75 → none.
        assert_eq!(pairs, vec![(0, 3), (3, 4)]);
    }

    #[test]
    fn path_pairs_all_take_the_nearest_distance_within_ten_percent() {
        // Accumulated: 0, 0.5, 0.75, 1.25, 2.25, 2.75, 3.0, 3.0 (a stop at the end).
        let poses = along_x(&[0.5, 0.25, 0.5, 1.0, 0.5, 0.25, 0.0]);
        let pairs = pose_pairs(&poses, &options(1.0, DeltaUnit::Meters, true)).unwrap();
        // i=0: 0.75 vs 1.25 equally far (0.25) > 0.1 → none. i=1: 0.75 vs 1.75 → none.
        // i=2: from 0.75, distances 0.5, 1.5 → none. i=3: 1.0 exactly → (3, 4).
        // i=4: 0.5, 0.75, 0.75 → none. i=5: 0.25, 0.25 → none. i=6: 0.0 → none.
        assert_eq!(pairs, vec![(3, 4)]);

        let poses = along_x(&[0.25; 8]);
        let pairs = pose_pairs(&poses, &options(0.5, DeltaUnit::Meters, true)).unwrap();
        assert_eq!(pairs, (0..7).map(|i| (i, i + 2)).collect::<Vec<_>>());
    }

    #[test]
    fn path_pairs_all_prefer_the_first_of_equal_distances() {
        // Accumulated 0, 0.95, 0.95, 0.95, 2.0: the nearest to 1.0 is 0.95, first at index 1.
        let poses = along_x(&[0.95, 0.0, 0.0, 1.05]);
        let pairs = pose_pairs(&poses, &options(1.0, DeltaUnit::Meters, true)).unwrap();
        assert_eq!(pairs[0], (0, 1));
        // From index 1 the nearest is 2.0 − 0.95 = 1.05 at index 4.
        assert_eq!(pairs[1], (1, 4));
    }

    #[test]
    fn angle_pairs_consecutive_and_all() {
        // Headings 0, 4, 8, 12, 22.5, 24.5 degrees.
        let poses = turning(&[4.0, 4.0, 4.0, 10.5, 2.0]);
        let consecutive = pose_pairs(&poses, &options(10.0, DeltaUnit::Degrees, false)).unwrap();
        assert_eq!(consecutive, vec![(0, 3), (3, 4)]);
        // Direct angles within [9°, 11°]: only (3, 4) at 10.5° ((1, 3) is 8°, (0, 3) 12°).
        let all = pose_pairs(&poses, &options(10.0, DeltaUnit::Degrees, true)).unwrap();
        assert_eq!(all, vec![(3, 4)]);
    }

    #[test]
    fn bad_deltas_and_empty_pair_lists_are_errors() {
        let poses = along_x(&[1.0, 1.0]);
        let err = pose_pairs(&poses, &options(1.5, DeltaUnit::Frames, false)).unwrap_err();
        assert_eq!(
            err.to_string(),
            "delta = 1.5: expected a whole number of frames >= 1"
        );
        let err = pose_pairs(&poses, &options(200.0, DeltaUnit::Degrees, false)).unwrap_err();
        assert_eq!(
            err.to_string(),
            "delta = 200: expected an angle in degrees in (0, 180]"
        );
        let err = pose_pairs(&poses, &options(5.0, DeltaUnit::Frames, false)).unwrap_err();
        assert_eq!(
            err.to_string(),
            "RPE: delta = 5 (frames) gives no pose pair among 3 associated poses; try a smaller delta"
        );
    }
}
