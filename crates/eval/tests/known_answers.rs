//! End-to-end cases with answers known by construction.

use glam::{DQuat, DVec3};
use rslam_core::trajectory_io::{write_replica, write_tum, ReadOptions};
use rslam_core::{Pose, Trajectory};
use rslam_eval::{evaluate, read_and_evaluate, AlignMode, EvalError, EvalOptions, Matching};

/// Errors that must vanish for exact (noise-free) data: rounding only.
const ZERO_TOL: f64 = 1e-9;

/// A 30 Hz camera on a wavy loop, turning as it goes.
fn loop_trajectory(n: usize) -> Trajectory {
    let poses = (0..n)
        .map(|i| {
            let s = i as f64 / 30.0;
            Pose::new(
                DQuat::from_euler(
                    glam::EulerRot::ZYX,
                    0.8 * s,
                    0.1 * (3.0 * s).sin(),
                    0.05 * s,
                ),
                DVec3::new(
                    2.0 * (0.5 * s).cos(),
                    1.5 * (0.5 * s).sin(),
                    0.2 * (1.7 * s).sin(),
                ),
            )
        })
        .collect();
    Trajectory::from_poses_at_rate(poses, 30.0)
}

/// `world_from_old` applied to every pose, translations scaled by `scale` first.
fn moved(t: &Trajectory, world_from_old: Pose, scale: f64) -> Trajectory {
    let poses = t
        .poses
        .iter()
        .map(|p| world_from_old.compose(&Pose::new(p.rotation, p.translation * scale)))
        .collect();
    Trajectory::new(t.timestamps.clone(), poses)
}

fn some_transform() -> Pose {
    Pose::new(
        DQuat::from_euler(glam::EulerRot::XYZ, 0.7, -1.2, 2.5),
        DVec3::new(10.0, -3.0, 4.0),
    )
}

#[test]
fn rigidly_moved_copy_has_zero_error_after_se3_alignment() {
    let gt = loop_trajectory(300);
    let est = moved(&gt, some_transform(), 1.0);
    let e = evaluate(&est, &gt, &EvalOptions::default()).unwrap();
    assert_eq!(e.pairs, 300);
    assert!(e.ate.max < ZERO_TOL, "ATE {}", e.ate.max);
    assert!(e.rpe_trans.max < ZERO_TOL && e.rpe_rot_deg.max < 1e-6);
    assert_eq!(e.success_rate.sr, Some(1.0));
    assert_eq!(e.success_rate.tracked_fraction, 1.0);
    assert!((e.success_rate.sr_path_ratio.unwrap() - 1.0).abs() < ZERO_TOL);
    // The alignment found is the inverse of the applied transform.
    let inverse = some_transform().inverse();
    let applied = e.alignment.apply(DVec3::new(1.0, 2.0, 3.0));
    assert!((applied - inverse.transform_point(DVec3::new(1.0, 2.0, 3.0))).length() < ZERO_TOL);

    // Without alignment the error is the displacement.
    let none = EvalOptions {
        align: AlignMode::None,
        ..EvalOptions::default()
    };
    assert!(evaluate(&est, &gt, &none).unwrap().ate.min > 1.0);
}

#[test]
fn sim3_recovers_a_known_scale() {
    let gt = loop_trajectory(200);
    let est = moved(&gt, some_transform(), 0.37);
    let sim3 = EvalOptions {
        align: AlignMode::Sim3,
        ..EvalOptions::default()
    };
    let e = evaluate(&est, &gt, &sim3).unwrap();
    assert!((e.alignment.scale - 1.0 / 0.37).abs() < ZERO_TOL);
    assert!(e.ate.max < ZERO_TOL);
    assert!(e.rpe_trans.max < ZERO_TOL);
    assert!(
        (e.success_rate.sr_path_ratio.unwrap() - 1.0).abs() < ZERO_TOL,
        "the path ratio is scaled by the Sim(3) scale"
    );
    // SE(3) cannot fix the scale; SR does not depend on it.
    let se3 = evaluate(&est, &gt, &EvalOptions::default()).unwrap();
    assert!(se3.ate.rmse > 0.1);
    assert!((se3.success_rate.sr_path_ratio.unwrap() - 0.37).abs() < ZERO_TOL);
    assert_eq!(
        (e.success_rate.sr, se3.success_rate.sr),
        (Some(1.0), Some(1.0))
    );
}

/// The ground truth with every position pushed `amplitude` metres along z, up and down on
/// alternate frames.
fn jittered(t: &Trajectory, amplitude: f64) -> Trajectory {
    let poses = t
        .poses
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
            Pose::new(p.rotation, p.translation + DVec3::Z * sign * amplitude)
        })
        .collect();
    Trajectory::new(t.timestamps.clone(), poses)
}

#[test]
fn heavy_jitter_keeps_sr_at_one_and_inflates_the_path_ratio() {
    let gt = loop_trajectory(300);
    // ±1 cm on ~3.3 cm of motion per frame: each step gains a 2 cm detour.
    let e = evaluate(&jittered(&gt, 0.01), &gt, &EvalOptions::default()).unwrap();
    assert_eq!(e.success_rate.sr, Some(1.0));
    let ratio = e.success_rate.sr_path_ratio.unwrap();
    assert!(ratio > 1.1, "path ratio {ratio}");
    assert!((e.ate.rmse - 0.01).abs() < 1e-3, "ATE {}", e.ate.rmse);
}

#[test]
fn a_lost_tracker_repeating_its_last_pose_covers_the_path_but_shows_in_ate() {
    let gt = loop_trajectory(300);
    let mut est = gt.clone();
    let last_tracked = est.poses[149];
    est.poses[150..].fill(last_tracked);
    let e = evaluate(&est, &gt, &EvalOptions::default()).unwrap();
    assert_eq!(e.success_rate.sr, Some(1.0));
    assert_eq!(e.success_rate.tracked_fraction, 1.0);
    assert!(e.ate.rmse > 0.5, "ATE {}", e.ate.rmse);
    let first_half = Trajectory::new(gt.timestamps[..150].to_vec(), gt.poses[..150].to_vec());
    let expected = first_half.path_length() / gt.path_length();
    assert!((e.success_rate.sr_path_ratio.unwrap() - expected).abs() < ZERO_TOL);
}

#[test]
fn estimate_that_stops_early_covers_the_path_it_tracked() {
    let gt = loop_trajectory(300);
    let est = Trajectory::new(gt.timestamps[..150].to_vec(), gt.poses[..150].to_vec());
    let e = evaluate(&est, &gt, &EvalOptions::default()).unwrap();
    assert_eq!((e.pairs, e.max_pairs), (150, 150));
    let s = &e.success_rate;
    let expected = est.path_length() / gt.path_length();
    assert!(expected < 0.6);
    assert!((s.sr.unwrap() - expected).abs() < 1e-15);
    assert!((s.sr_path_ratio.unwrap() - expected).abs() < 1e-15);
    assert_eq!((s.tracked_poses, s.ground_truth_poses), (150, 300));
    assert_eq!(s.tracked_fraction, 0.5);
}

#[test]
fn stamps_off_by_more_than_max_diff_give_a_clear_error_and_t_offset_fixes_it() {
    let gt = loop_trajectory(100);
    let mut est = gt.clone();
    est.timestamps.iter_mut().for_each(|t| *t += 100.0);
    let err = evaluate(&est, &gt, &EvalOptions::default()).unwrap_err();
    assert!(matches!(err, EvalError::NoMatches { .. }));
    assert!(
        err.to_string().starts_with(
            "no matching timestamps: no estimate pose lies within 0.01 s of a ground-truth pose \
             (t-offset 0 s); the estimate spans 100.000000 .. 103.300000 s, the ground truth 0.000000 .. 3.300000 s"
        ),
        "{err}"
    );
    let shifted = EvalOptions {
        matching: Matching::Time {
            max_diff: 0.01,
            t_offset: -100.0,
        },
        ..EvalOptions::default()
    };
    let e = evaluate(&est, &gt, &shifted).unwrap();
    assert_eq!(e.pairs, 100);
    assert!(e.ate.max < ZERO_TOL);
}

#[test]
fn static_ground_truth_cannot_be_aligned() {
    let still = Trajectory::from_poses_at_rate(vec![Pose::IDENTITY; 20], 30.0);
    let err = evaluate(&still, &still, &EvalOptions::default()).unwrap_err();
    assert!(
        err.to_string().contains("degenerate (they do not move)"),
        "{err}"
    );
    let none = EvalOptions {
        align: AlignMode::None,
        ..EvalOptions::default()
    };
    let e = evaluate(&still, &still, &none).unwrap();
    assert_eq!(
        (e.success_rate.sr, e.success_rate.sr_path_ratio),
        (None, None)
    );
}

#[test]
fn files_of_different_formats_evaluate_together() {
    let dir = tempfile::tempdir().unwrap();
    // Replica at 20 Hz against TUM stamped at 20 Hz: associated by time.
    let gt = Trajectory::from_poses_at_rate(loop_trajectory(120).poses, 20.0);
    let replica = dir.path().join("traj.txt");
    write_replica(&replica, &gt).unwrap();
    let tum = dir.path().join("est.txt");
    write_tum(&tum, &moved(&gt, some_transform(), 1.0)).unwrap();
    let e = read_and_evaluate(
        &tum,
        &replica,
        &ReadOptions::default(),
        &EvalOptions::default(),
    )
    .unwrap();
    assert_eq!(e.pairs, 120);
    assert!(e.ate.max < 1e-6);

    // KITTI has no time: matched by index, the longer file's extra poses unused.
    let kitti = dir.path().join("00.txt");
    let rows: String = gt.poses[..100]
        .iter()
        .map(|p| {
            let m = p.to_row_major();
            m[..12]
                .iter()
                .map(|v| format!("{v:.17e}"))
                .collect::<Vec<_>>()
                .join(" ")
                + "\n"
        })
        .collect();
    std::fs::write(&kitti, rows).unwrap();
    let e = read_and_evaluate(
        &kitti,
        &replica,
        &ReadOptions::default(),
        &EvalOptions::default(),
    )
    .unwrap();
    assert_eq!(e.options.matching, Matching::Index);
    assert_eq!((e.pairs, e.max_pairs), (100, 100));
    assert!(e.ate.max < ZERO_TOL);
}
