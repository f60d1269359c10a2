//! The spec's motion items on rigs: `fast` plays the rig's path faster (frames, ground truth and
//! IMU alike), `rot`/`trans` deviate it, `misalign` delays the depth of an `rgbd-imu` rig.

use std::collections::HashMap;

use glam::DVec3;
use rslam_core::dataset::euroc::{read_euroc, EurocDataset, GroundTruthState};

use crate::dataset_check::lines;
use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;
use crate::rig_calibration::{grey, mean_abs_difference};

const GRAVITY_W: DVec3 = DVec3::new(0.0, 0.0, -9.81);

/// room0's path, `poses` of it at 20 Hz, seen by `rig` in the EuRoC layout.
fn render_rig(
    ws: &Workspace,
    out: &str,
    rig: &str,
    poses: &str,
    spec: Option<&str>,
) -> EurocDataset {
    let args = [
        "--frames", poses, "--rate", "20", "--rig", rig, "--format", "euroc",
    ];
    ws.render_room0(out, &args, spec);
    read_euroc(&ws.path(out)).unwrap()
}

fn by_time(states: &[GroundTruthState]) -> HashMap<u64, &GroundTruthState> {
    states.iter().map(|s| (s.t_ns, s)).collect()
}

/// Under `fast:2` the path's stamps are halved, so the motion at time t is the clean motion at
/// 2t: cam0's frame k is the clean frame 2k, the body is where it was at 2t with twice the
/// velocity, the gyroscope reads twice the rate and the acceleration (specific force plus
/// gravity, in the IMU frame) is four times as large.
#[test]
fn fast_plays_the_rigs_motion_faster_for_every_sensor() {
    let ws = Workspace::new();
    let clean = render_rig(&ws, "clean", "stereo-imu", "24", Some("imu_noise:0"));
    let fast = render_rig(&ws, "fast", "stereo-imu", "24", Some("imu_noise:0,fast:2"));

    // 24 poses at 20 Hz: the clean spline is valid over 21 / 20 s (22 frames), the fast one
    // over 21 / 40 s (11 frames).
    assert_eq!(clean.cameras[0].frames.len(), 22);
    assert_eq!(fast.cameras[0].frames.len(), 11);
    assert_eq!(fast.cameras[1].frames.len(), 11);
    for (k, frame) in fast.cameras[0].frames.iter().enumerate() {
        let twin = &clean.cameras[0].frames[2 * k];
        assert_eq!(twin.t_ns, 2 * frame.t_ns, "frame {k}");
        let same = mean_abs_difference(&grey(&frame.path), &grey(&twin.path));
        assert!(
            same < 0.05,
            "frame {k}: {same} grey levels from clean frame {}",
            2 * k
        );
        if k >= 2 {
            let other =
                mean_abs_difference(&grey(&frame.path), &grey(&clean.cameras[0].frames[k].path));
            assert!(
                other > 20.0 * same.max(0.01),
                "frame {k} vs clean frame {k}: {other}"
            );
        }
    }

    let clean_truth = clean.ground_truth.as_ref().unwrap();
    let fast_truth = fast.ground_truth.as_ref().unwrap();
    let clean_at = by_time(clean_truth);
    let clean_imu: HashMap<u64, _> = clean
        .imu
        .as_ref()
        .unwrap()
        .samples
        .iter()
        .map(|s| (s.t_ns, s))
        .collect();
    let fast_imu = &fast.imu.as_ref().unwrap().samples;
    assert_eq!(fast_imu.len(), fast_truth.len());
    let mut compared = 0;
    for (state, reading) in fast_truth.iter().zip(fast_imu) {
        let (Some(twin), Some(twin_reading)) = (
            clean_at.get(&(2 * state.t_ns)),
            clean_imu.get(&(2 * state.t_ns)),
        ) else {
            continue;
        };
        compared += 1;
        let pose = state.world_from_body;
        assert!((pose.translation - twin.world_from_body.translation).length() < 1e-6);
        assert!(pose.rotation.angle_between(twin.world_from_body.rotation) < 1e-6);
        assert!((state.velocity - 2.0 * twin.velocity).length() < 1e-6);
        assert!((reading.gyro - 2.0 * twin_reading.gyro).length() < 1e-5);
        let gravity_b = pose.rotation.inverse() * GRAVITY_W;
        let felt = |accel: DVec3| accel + gravity_b;
        assert!((felt(reading.accel) - 4.0 * felt(twin_reading.accel)).length() < 1e-4);
    }
    assert_eq!(
        compared,
        fast_truth.len(),
        "every fast sample has a clean twin at 2t"
    );
    assert!(compared > 100, "{compared}");
}

/// `trans:σ` deviates cam0's path pose by pose (i.i.d., per world axis); the body follows, and
/// the spline through the deviated poses weighs each knot's neighbours 1/6, 2/3, 1/6, so at the
/// knots the written ground truth departs from the clean one by √(1/36 + 4/9 + 1/36) σ = 0.707 σ
/// per axis. `rot:D` turns the body by 0.707 D per axis the same way.
#[test]
fn rot_and_trans_deviate_the_rigs_ground_truth() {
    const SIGMA_M: f64 = 0.02;
    const SIGMA_DEG: f64 = 2.0;
    let ws = Workspace::new();
    let clean = render_rig(&ws, "clean", "stereo", "100", None);
    let spec = format!("trans:{SIGMA_M},rot:{SIGMA_DEG}");
    let moved = render_rig(&ws, "moved", "stereo", "100", Some(&spec));
    let (clean, moved) = (clean.ground_truth.unwrap(), moved.ground_truth.unwrap());
    // Without an IMU the ground truth is at cam0's frames, which fall on the path's poses.
    assert_eq!(clean.len(), 98);
    assert_eq!(moved.len(), clean.len());
    let (mut squared_m, mut squared_deg) = (0.0, 0.0);
    for (c, m) in clean.iter().zip(&moved) {
        assert_eq!(c.t_ns, m.t_ns);
        let offset = m.world_from_body.translation - c.world_from_body.translation;
        squared_m += offset.length_squared();
        let turn = c
            .world_from_body
            .rotation
            .angle_between(m.world_from_body.rotation);
        squared_deg += turn.to_degrees().powi(2);
    }
    let n = clean.len() as f64;
    // rms per axis, over 294 draws each: a standard error of about 4 %
    let per_axis_m = (squared_m / (3.0 * n)).sqrt();
    let per_axis_deg = (squared_deg / (3.0 * n)).sqrt();
    let expected = 0.5f64.sqrt();
    assert!(
        (per_axis_m / SIGMA_M - expected).abs() < 0.15 * expected,
        "translation: {per_axis_m} m per axis for σ = {SIGMA_M}"
    );
    assert!(
        (per_axis_deg / SIGMA_DEG - expected).abs() < 0.15 * expected,
        "rotation: {per_axis_deg}° per axis for σ = {SIGMA_DEG}°"
    );
}

/// `misalign:D` on `rgbd-imu` pairs colour frame i with the depth of frame i − D, each keeping
/// its capture time, as for one camera; the IMU is not affected.
#[test]
fn misalign_delays_the_depth_of_an_rgbd_imu_rig() {
    let ws = Workspace::new();
    let args = |spec: &'static str, out: &'static str| {
        vec![
            "render",
            "--scene",
            "room0",
            "--frames",
            "12",
            "--camera",
            SMALL_CAMERA,
            "--rate",
            "30",
            "--format",
            "tum",
            "--rig",
            "rgbd-imu",
            "--perturb",
            spec,
            "--out",
            out,
        ]
    };
    ws.rslam(&args("misalign:2", "lag")).success();
    ws.rslam(&args("fog:1", "plain")).success();
    let assoc = lines(&ws.path("lag/associations.txt"));
    let plain = lines(&ws.path("plain/associations.txt"));
    assert_eq!(assoc.len(), plain.len());
    assert!(assoc.len() >= 6, "{assoc:?}");
    let field = |line: &str, i: usize| line.split(' ').nth(i).unwrap().to_string();
    for (i, line) in assoc.iter().enumerate() {
        assert_eq!(field(line, 0), field(&plain[i], 0), "colour keeps its time");
        let source = i.saturating_sub(2);
        assert_eq!(field(line, 2), field(&plain[source], 2), "line {i}: {line}");
    }
    assert_eq!(
        std::fs::read(ws.path("lag/imu0/data.csv")).unwrap(),
        std::fs::read(ws.path("plain/imu0/data.csv")).unwrap()
    );
}
