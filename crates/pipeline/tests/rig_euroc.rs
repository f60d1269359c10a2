//! A stereo-IMU rig rendered into the EuRoC layout and read back: the streams, the calibration,
//! and that the two cameras' images form a real stereo pair at the written baseline.

use std::sync::OnceLock;

use glam::DVec3;
use rslam_core::dataset::euroc::{read_euroc, CameraColour, EurocDataset, GroundTruthState};
use rslam_core::dataset::{read_image_has_colour, read_image_size, read_rgb, Layout};
use rslam_core::{DepthImage, Pose, RgbImage};
use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_perturb::PerturbSpec;
use rslam_pipeline::rig::{EUROC_CAM0_INTRINSICS, STEREO_BASELINE_M};
use rslam_pipeline::{
    run, FolderState, FramesInMemory, Job, Rig, SceneJob, Sensors, Silent, Source, Streams,
};

/// Poses of room0's path rendered; the spline's valid range drops the first and last.
const PATH_POSES: usize = 6;
const FRAME_NS: u64 = 50_000_000;
const IMU_NS: u64 = 5_000_000;
/// Rounding of seconds to whole nanoseconds.
const NS_SLACK: u64 = 1;
/// T_BS and ground truth are written as decimal text.
const CALIBRATION_TOLERANCE_M: f64 = 1e-9;
const UNIT_QUATERNION_TOLERANCE: f64 = 1e-9;

fn context() -> &'static GpuContext {
    static CONTEXT: OnceLock<GpuContext> = OnceLock::new();
    CONTEXT.get_or_init(|| {
        GpuContext::new(&AdapterChoice::default())
            .unwrap_or_else(|e| panic!("these tests need an adapter (lavapipe is fine): {e}"))
    })
}

fn scene_job(frames: Option<usize>) -> SceneJob {
    SceneJob {
        scene: "room0".into(),
        trajectory: None,
        frames,
        camera: EUROC_CAM0_INTRINSICS,
        rate_hz: 20.0,
        spec: PerturbSpec::default(),
        seed: 5,
        agent: None,
        capture: Default::default(),
        actor_files: Vec::new(),
    }
}

fn grey(image: &RgbImage) -> Vec<f64> {
    image
        .data
        .chunks_exact(3)
        .map(|p| (0.299 * p[0] as f64 + 0.587 * p[1] as f64 + 0.114 * p[2] as f64).round())
        .collect()
}

fn median(mut values: Vec<f64>) -> f64 {
    assert!(!values.is_empty());
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// `image` at column `x` (linear between pixels) of row `y`; `None` outside.
fn sample_row(image: &[f64], width: usize, x: f64, y: usize) -> Option<f64> {
    let x0 = x.floor();
    if x0 < 0.0 || x0 + 1.0 > (width - 1) as f64 {
        return None;
    }
    let (i, a) = (x0 as usize, x - x0);
    Some(image[y * width + i] * (1.0 - a) + image[y * width + i + 1] * a)
}

/// Median |cam0(x, y) − cam1(x + sign · f·b/z, y)| over cam0 pixels with depth and a strong
/// horizontal gradient (plain walls match at any shift), and how many pixels it covers.
fn stereo_mismatch(cam0: &[f64], cam1: &[f64], depth: &DepthImage, sign: f64) -> (f64, usize) {
    let (w, h) = (depth.width as usize, depth.height as usize);
    let fb = EUROC_CAM0_INTRINSICS.fx * STEREO_BASELINE_M;
    let mut diffs = Vec::new();
    for y in 0..h {
        for x in 1..w - 1 {
            let z = depth.data[y * w + x] as f64;
            let gradient = (cam0[y * w + x + 1] - cam0[y * w + x - 1]).abs();
            if z <= 0.0 || gradient < 16.0 {
                continue;
            }
            if let Some(v) = sample_row(cam1, w, x as f64 + sign * fb / z, y) {
                diffs.push((cam0[y * w + x] - v).abs());
            }
        }
    }
    let count = diffs.len();
    (median(diffs), count)
}

fn ground_truth_at(data: &EurocDataset, t_ns: u64) -> GroundTruthState {
    *data
        .ground_truth
        .as_ref()
        .unwrap()
        .iter()
        .find(|s| s.t_ns == t_ns)
        .unwrap_or_else(|| panic!("no ground-truth row at {t_ns} ns"))
}

#[test]
fn stereo_imu_rig_writes_a_euroc_stereo_pair_with_imu_and_ground_truth() {
    let ctx = context();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rig");
    let job = Job {
        source: Source::Scene {
            scene: scene_job(Some(PATH_POSES)),
            sensors: Sensors::Rig(Rig::stereo_imu(), Layout::Euroc, Default::default()),
        },
        out: out.clone(),
        force: false,
        command: vec!["test".into()],
    };
    let report = run(ctx, &job, &Silent).unwrap();
    assert_eq!(report.found, FolderState::Fresh);
    let Streams::Rig {
        cameras,
        imu_samples,
    } = report.streams
    else {
        panic!("a rig's streams: {:?}", report.streams)
    };
    assert!(out.join("rslam.json").is_file());
    assert!(!out.join("rslam.run.json").exists());

    let data = read_euroc(&out).unwrap();
    // Two cameras, the same frame times, at 20 Hz.
    assert_eq!(data.cameras.len(), 2);
    let (cam0, cam1) = (&data.cameras[0], &data.cameras[1]);
    assert_eq!(
        (cam0.camera.name.as_str(), cam1.camera.name.as_str()),
        ("cam0", "cam1")
    );
    let times: Vec<u64> = cam0.frames.iter().map(|f| f.t_ns).collect();
    assert_eq!(
        times,
        cam1.frames.iter().map(|f| f.t_ns).collect::<Vec<_>>()
    );
    assert_eq!(times.len(), PATH_POSES - 2, "{times:?}");
    assert_eq!(cameras[0].frames, times.len());
    for pair in times.windows(2) {
        assert!(
            (pair[1] - pair[0]).abs_diff(FRAME_NS) <= NS_SLACK,
            "{times:?}"
        );
    }
    // Grey 752×480 PNGs, as the sensor.yaml says.
    for stream in [cam0, cam1] {
        assert_eq!(stream.camera.colour, CameraColour::Grey);
        assert_eq!(
            (
                stream.camera.intrinsics.width,
                stream.camera.intrinsics.height
            ),
            (752, 480)
        );
        for frame in &stream.frames {
            assert_eq!(read_image_size(&frame.path).unwrap(), (752, 480));
            assert!(!read_image_has_colour(&frame.path).unwrap());
        }
    }
    // cam1 is cam0 moved 0.11 m along cam0's x axis, axes parallel.
    let cam0_from_cam1 = cam0
        .camera
        .body_from_camera
        .inverse()
        .compose(&cam1.camera.body_from_camera);
    let baseline = cam0_from_cam1.translation - DVec3::X * STEREO_BASELINE_M;
    assert!(
        baseline.length() < CALIBRATION_TOLERANCE_M,
        "{cam0_from_cam1:?}"
    );
    assert!(cam0_from_cam1.rotation.angle_between(glam::DQuat::IDENTITY) < 1e-9);
    // cam0 sits where EuRoC MH_01's cam0 sits on its IMU.
    let t_bs = cam0.camera.body_from_camera.translation;
    assert!(
        (t_bs - DVec3::new(-0.0216401454975, -0.064676986768, 0.00981073058949)).length() < 1e-9
    );

    // IMU at 200 Hz over the frames, ground truth at the IMU's times with unit quaternions.
    let imu = &data.imu.as_ref().unwrap().samples;
    assert_eq!(imu_samples, imu.len());
    for pair in imu.windows(2) {
        assert!((pair[1].t_ns - pair[0].t_ns).abs_diff(IMU_NS) <= NS_SLACK);
    }
    assert!(
        imu[0].t_ns <= times[0] && imu.last().unwrap().t_ns + NS_SLACK >= *times.last().unwrap()
    );
    let at_rest = imu.iter().map(|s| s.accel.length()).sum::<f64>() / imu.len() as f64;
    assert!(
        (at_rest - 9.81).abs() < 2.0,
        "mean |a| {at_rest}: gravity should dominate"
    );
    let states = data.ground_truth.as_ref().unwrap();
    assert_eq!(states.len(), imu.len());
    for (state, sample) in states.iter().zip(imu) {
        assert_eq!(state.t_ns, sample.t_ns);
        let q = state.world_from_body.rotation;
        assert!(
            (q.length() - 1.0).abs() < UNIT_QUATERNION_TOLERANCE,
            "{q:?}"
        );
    }

    // The images: cam0 is the scene from the written pose; cam1 a true right camera.
    let k = 1;
    let body = ground_truth_at(&data, times[k]).world_from_body;
    let poses: Vec<Pose> = [cam0, cam1]
        .iter()
        .map(|c| body.compose(&c.camera.body_from_camera))
        .collect();
    let mut frames = FramesInMemory::scene_along(ctx, &scene_job(None), poses).unwrap();
    let rendered0 = frames.frame(ctx, 0).unwrap();
    let depth = rendered0.depth.unwrap();
    let written0 = grey(&read_rgb(&cam0.frames[k].path).unwrap());
    let written1 = grey(&read_rgb(&cam1.frames[k].path).unwrap());
    let same: Vec<f64> = grey(&rendered0.color)
        .iter()
        .zip(&written0)
        .map(|(a, b)| (a - b).abs())
        .collect();
    let same_mean = same.iter().sum::<f64>() / same.len() as f64;
    assert!(
        same_mean < 1.0,
        "cam0 frame vs a render at its ground-truth pose: mean |Δ| {same_mean}"
    );

    let (right, compared) = stereo_mismatch(&written0, &written1, &depth, -1.0);
    let (wrong, _) = stereo_mismatch(&written0, &written1, &depth, 1.0);
    eprintln!("stereo: median |Δ| {right} at x − f·b/z, {wrong} at x + f·b/z, {compared} pixels");
    assert!(compared > 2000, "{compared} textured pixels with depth");
    assert!(right <= 4.0, "cam1 at x − f·b/z: median |Δ| {right}");
    assert!(
        wrong >= 3.0 * right.max(2.0),
        "x + f·b/z: median |Δ| {wrong}, x − f·b/z: {right}"
    );
}
