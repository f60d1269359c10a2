//! Throughput of `rslam eval` on a 100 000-pose pair: association + SE(3) alignment + ATE + RPE,
//! in memory and from TUM files (parsing included).
//!
//! Set `RSLAM_BENCH_FILES=DIR` to time `DIR/est.txt` against `DIR/gt.txt` instead of generated
//! files; `evo_compare.sh` uses that to time rslam and evo on the same files.

use std::path::PathBuf;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::{DQuat, DVec3};
use rslam_core::trajectory_io::{write_tum, ReadOptions};
use rslam_core::{Pose, Trajectory};
use rslam_eval::{evaluate, read_and_evaluate, EvalOptions};

const POSES: usize = 100_000;
const RATE_HZ: f64 = 100.0;

/// A 100 Hz walk with a turning camera; the estimate is the same path, slightly wrong, moved to
/// another frame, with stamps jittered by up to ±3 ms.
fn pair() -> (Trajectory, Trajectory) {
    let pose = |s: f64, wobble: f64| {
        Pose::new(
            DQuat::from_euler(
                glam::EulerRot::ZYX,
                0.3 * s + wobble,
                0.1 * (0.7 * s).sin(),
                0.0,
            ),
            DVec3::new(
                3.0 * (0.05 * s).cos() + wobble,
                2.0 * (0.05 * s).sin(),
                0.02 * s,
            ),
        )
    };
    let gt = Trajectory::from_poses_at_rate(
        (0..POSES).map(|i| pose(i as f64 / RATE_HZ, 0.0)).collect(),
        RATE_HZ,
    );
    let frame = Pose::new(DQuat::from_rotation_y(0.4), DVec3::new(1.0, 2.0, 3.0));
    let stamps: Vec<f64> = (0..POSES)
        .map(|i| i as f64 / RATE_HZ + 0.003 * ((i * 7919) % 13) as f64 / 6.0 - 0.003)
        .collect();
    let poses = stamps
        .iter()
        .map(|&t| frame.compose(&pose(t, 0.01 * (3.1 * t).sin())))
        .collect();
    (Trajectory::new(stamps, poses), gt)
}

fn bench(c: &mut Criterion) {
    let options = EvalOptions::default();
    let mut group = c.benchmark_group("eval");
    group.sample_size(10);
    group.throughput(Throughput::Elements(POSES as u64));

    let (est, gt) = pair();
    group.bench_function("ate_rpe_100k_in_memory", |b| {
        b.iter(|| evaluate(&est, &gt, &options).unwrap())
    });

    let keep = tempfile::tempdir().unwrap();
    let dir = std::env::var_os("RSLAM_BENCH_FILES").map_or_else(
        || {
            write_tum(&keep.path().join("est.txt"), &est).unwrap();
            write_tum(&keep.path().join("gt.txt"), &gt).unwrap();
            keep.path().to_path_buf()
        },
        PathBuf::from,
    );
    let (est_path, gt_path) = (dir.join("est.txt"), dir.join("gt.txt"));
    let read = ReadOptions::default();
    group.bench_function("ate_rpe_100k_from_tum_files", |b| {
        b.iter(|| read_and_evaluate(&est_path, &gt_path, &read, &options).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
