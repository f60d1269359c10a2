//! Per-sensor perturbations of a rendered rig: an item addressed to one camera, and the
//! calibration items in their two modes (`baseline:σ` measured in the disparity of the rendered
//! pair, `@calibration` in the written files only, `@dynamic` per frame).

use std::path::{Path, PathBuf};

use glam::{DQuat, DVec3};
use rslam_core::dataset::euroc::read_euroc;
use rslam_core::dataset::{
    decode_depth_png, read_dataset, DatasetFormat, DatasetOverrides, Manifest,
};
use rslam_core::{DepthImage, Intrinsics, Pose};

use crate::dataset_check::assert_poses_close;
use crate::harness::Workspace;

const NOMINAL_BASELINE_M: f64 = 0.11;
/// Large enough that the drawn δ moves the disparity far beyond the measurement's error.
const BASELINE_SIGMA: &str = "0.03";
/// Median disparity ratio measured vs (b + δ) / b.
const RATIO_TOLERANCE: f64 = 0.02;

fn render(ws: &Workspace, out: &str, rig: &str, perturb: Option<&str>) {
    ws.render_room0(
        out,
        &["--frames", "4", "--rig", rig, "--format", "euroc"],
        perturb,
    );
}

/// The frames of one camera, in time order (`<t_ns>.png`).
pub(crate) fn frames(root: &Path, camera: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root.join("mav0").join(camera).join("data"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    let t_ns = |p: &PathBuf| -> u64 { p.file_stem().unwrap().to_str().unwrap().parse().unwrap() };
    files.sort_by_key(t_ns);
    assert!(!files.is_empty(), "{camera} has no frames");
    files
}

/// The one `error:` line of a failed run (the adapter line comes before it).
fn one_error_line(stderr: &str) {
    let errors = stderr.lines().filter(|l| l.starts_with("error:")).count();
    assert_eq!(errors, 1, "{stderr}");
}

fn same_bytes(a: &Path, b: &Path) -> bool {
    std::fs::read(a).unwrap() == std::fs::read(b).unwrap()
}

fn calibration_record(root: &Path) -> serde_json::Value {
    Manifest::read(root).unwrap().extra["calibration"].clone()
}

/// cam1's position along cam0's x axis.
fn baseline_of(cam0: &Pose, cam1: &Pose) -> f64 {
    cam0.inverse().compose(cam1).translation.x
}

pub(crate) fn grey(path: &Path) -> image::GrayImage {
    image::open(path).unwrap().to_luma8()
}

/// Mean absolute difference of two grey images of one size, grey levels.
pub(crate) fn mean_abs_difference(a: &image::GrayImage, b: &image::GrayImage) -> f64 {
    let sum: f64 = a
        .pixels()
        .zip(b.pixels())
        .map(|(p, q)| (p.0[0] as f64 - q.0[0] as f64).abs())
        .sum();
    sum / (a.width() * a.height()) as f64
}

/// Disparity of the left image's pixel (x, y) in the right image by block matching along the
/// row (sum of absolute differences over a window, the right match at x − d), refined to a
/// sub-pixel by a parabola through the best cost and its neighbours. `None` where the window
/// has no texture or the best match is not clearly better than the others.
fn disparity(left: &image::GrayImage, right: &image::GrayImage, x: u32, y: u32) -> Option<f64> {
    const HALF: i64 = 5;
    const MAX_D: i64 = 90;
    let at = |img: &image::GrayImage, x: i64, y: i64| img.get_pixel(x as u32, y as u32)[0] as f64;
    let (x, y) = (x as i64, y as i64);
    let window = || (-HALF..=HALF).flat_map(|dy| (-HALF..=HALF).map(move |dx| (dx, dy)));
    let mean = window()
        .map(|(dx, dy)| at(left, x + dx, y + dy))
        .sum::<f64>()
        / 121.0;
    let spread = window()
        .map(|(dx, dy)| (at(left, x + dx, y + dy) - mean).abs())
        .sum::<f64>()
        / 121.0;
    if spread < 6.0 {
        return None;
    }
    let costs: Vec<f64> = (0..=MAX_D.min(x - HALF))
        .map(|d| {
            window()
                .map(|(dx, dy)| (at(left, x + dx, y + dy) - at(right, x + dx - d, y + dy)).abs())
                .sum()
        })
        .collect();
    let (best, &cost) = costs.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1))?;
    let runner_up = costs
        .iter()
        .enumerate()
        .filter(|(d, _)| d.abs_diff(best) > 2)
        .map(|(_, c)| *c)
        .fold(f64::INFINITY, f64::min);
    if best == 0 || best + 1 >= costs.len() || cost > 0.7 * runner_up {
        return None;
    }
    let (a, b, c) = (costs[best - 1], cost, costs[best + 1]);
    let curvature = a - 2.0 * b + c;
    let offset = if curvature > 0.0 {
        0.5 * (a - c) / curvature
    } else {
        0.0
    };
    Some(best as f64 + offset)
}

/// Median over textured pixels of disparity(left, moved) / disparity(left, nominal): for a
/// rectified pair it is (b + δ) / b at every depth. Returns it and the pixels used.
pub(crate) fn median_disparity_ratio(
    left: &image::GrayImage,
    nominal_right: &image::GrayImage,
    moved_right: &image::GrayImage,
) -> (f64, usize) {
    let mut ratios = Vec::new();
    for y in (20..left.height() - 20).step_by(12) {
        for x in (100..left.width() - 20).step_by(12) {
            let (Some(nominal), Some(moved)) = (
                disparity(left, nominal_right, x, y),
                disparity(left, moved_right, x, y),
            ) else {
                continue;
            };
            if nominal > 4.0 {
                ratios.push(moved / nominal);
            }
        }
    }
    ratios.sort_by(f64::total_cmp);
    (ratios[ratios.len() / 2], ratios.len())
}

#[test]
fn an_item_addressed_to_cam1_changes_cam1_frames_only() {
    let ws = Workspace::new();
    render(&ws, "clean", "stereo", None);
    render(&ws, "cam1", "stereo", Some("cam1:gaussian_noise:3"));
    let (clean, noisy) = (ws.path("clean"), ws.path("cam1"));
    for (a, b) in frames(&clean, "cam0").iter().zip(frames(&noisy, "cam0")) {
        assert!(same_bytes(a, &b), "{} changed", b.display());
    }
    for (a, b) in frames(&clean, "cam1").iter().zip(frames(&noisy, "cam1")) {
        assert!(!same_bytes(a, &b), "{} unchanged", b.display());
    }
    let manifest = Manifest::read(&noisy).unwrap();
    assert_eq!(manifest.perturbation, "cam1:gaussian_noise:3");
}

#[test]
fn sensor_prefixes_fail_with_one_line_errors() {
    let ws = Workspace::new();
    let rig = |spec: &str| {
        ws.rslam(&[
            "render",
            "--scene",
            "room0",
            "--frames",
            "4",
            "--rig",
            "stereo",
            "--format",
            "euroc",
            "--perturb",
            spec,
            "--out",
            "x",
        ])
    };
    let err = rig("cam2:fog:3").fails_with(
        2,
        &["'cam2:fog:3': no sensor 'cam2' here; the sensors are cam0, cam1"],
    );
    one_error_line(&err);
    let err = rig("imu0:extrinsic_rot:1").fails_with(2, &["no sensor 'imu0'"]);
    one_error_line(&err);
    let err = rig("imu0:extrinsic_trans:0.01@dynamic").fails_with(
        2,
        &["'imu0:extrinsic_trans:0.01@dynamic': @dynamic moves a camera"],
    );
    one_error_line(&err);
    let err = rig("cam1:extrinsic_rot:1@dynamic@calibration")
        .fails_with(2, &["@dynamic and @calibration exclude each other"]);
    one_error_line(&err);
    assert!(!ws.path("x").join("rslam.json").exists());
    let one = |spec: &str| {
        ws.rslam(&[
            "render",
            "--scene",
            "room0",
            "--frames",
            "2",
            "--perturb",
            spec,
            "--out",
            "y",
        ])
    };
    let err = one("cam1:fog:3").fails_with(2, &["'cam1:fog:3': this input has one camera, cam0"]);
    one_error_line(&err);
    let err = one("baseline:0.01").fails_with(2, &["a calibration item needs a rig"]);
    one_error_line(&err);
    assert!(!ws.path("y").join("rslam.json").exists());
}

#[test]
fn baseline_in_rendered_mode_changes_the_disparity_by_the_drawn_amount() {
    let ws = Workspace::new();
    render(&ws, "clean", "stereo", None);
    let spec = format!("baseline:{BASELINE_SIGMA}");
    render(&ws, "moved", "stereo", Some(&spec));
    let (clean, moved) = (ws.path("clean"), ws.path("moved"));

    let record = calibration_record(&moved);
    let delta = record["baseline_offset_m"].as_f64().unwrap();
    assert!(
        delta.abs() > 0.01,
        "the fixture needs a large draw, got {delta}"
    );
    let baseline = &record["baseline_m"];
    assert!((baseline["true"].as_f64().unwrap() - (NOMINAL_BASELINE_M + delta)).abs() < 1e-9);
    assert!((baseline["written"].as_f64().unwrap() - NOMINAL_BASELINE_M).abs() < 1e-9);

    // The files state the nominal rig; cam0 sees what it saw.
    for file in [
        "mav0/cam0/sensor.yaml",
        "mav0/cam1/sensor.yaml",
        "orbslam3_stereo.yaml",
    ] {
        assert!(same_bytes(&clean.join(file), &moved.join(file)), "{file}");
    }
    let left = frames(&clean, "cam0")[0].clone();
    assert!(same_bytes(&left, &frames(&moved, "cam0")[0]));

    let (ratio, pixels) = median_disparity_ratio(
        &grey(&left),
        &grey(&frames(&clean, "cam1")[0]),
        &grey(&frames(&moved, "cam1")[0]),
    );
    let expected = (NOMINAL_BASELINE_M + delta) / NOMINAL_BASELINE_M;
    assert!(pixels > 200, "{pixels} matched pixels");
    assert!(
        (ratio / expected - 1.0).abs() < RATIO_TOLERANCE,
        "disparity ratio {ratio}, expected (b+δ)/b = {expected}"
    );
}

#[test]
fn calibration_mode_keeps_the_frames_and_moves_exactly_the_written_calibration() {
    let ws = Workspace::new();
    render(&ws, "clean", "stereo-imu", None);
    let spec = format!("baseline:{BASELINE_SIGMA}@calibration,imu0:extrinsic_rot:0.5@calibration");
    render(&ws, "written", "stereo-imu", Some(&spec));
    let (clean, written) = (ws.path("clean"), ws.path("written"));
    for camera in ["cam0", "cam1"] {
        for (a, b) in frames(&clean, camera).iter().zip(frames(&written, camera)) {
            assert!(same_bytes(a, &b), "{} changed", b.display());
        }
    }
    for file in [
        "mav0/imu0/data.csv",
        "mav0/state_groundtruth_estimate0/data.csv",
    ] {
        assert!(same_bytes(&clean.join(file), &written.join(file)), "{file}");
    }
    assert!(same_bytes(
        &clean.join("mav0/cam0/sensor.yaml"),
        &written.join("mav0/cam0/sensor.yaml")
    ));

    let record = calibration_record(&written);
    let delta = record["baseline_offset_m"].as_f64().unwrap();
    assert_eq!(record["baseline_mode"], "calibration");
    let nominal = read_euroc(&clean).unwrap();
    let read = read_euroc(&written).unwrap();
    let cam0 = read.cameras[0].camera.body_from_camera;
    let cam1 = read.cameras[1].camera.body_from_camera;
    let written_baseline = baseline_of(&cam0, &cam1);
    assert!(
        (written_baseline - (NOMINAL_BASELINE_M + delta)).abs() < 1e-9,
        "{written_baseline}"
    );
    // Only along the baseline: cam1's orientation and its other two axes are nominal.
    let nominal_cam1 = nominal.cameras[1].camera.body_from_camera;
    let moved = cam0.inverse().compose(&cam1).translation
        - cam0.inverse().compose(&nominal_cam1).translation;
    assert!((moved.x - delta).abs() < 1e-9 && moved.y.abs() < 1e-9 && moved.z.abs() < 1e-9);
    assert!(cam1.rotation.angle_between(nominal_cam1.rotation) < 1e-9);

    // imu0's written T_BS is the one the manifest records, and not the identity it is.
    let imu = read.imu.as_ref().unwrap().imu.body_from_imu;
    let sensors = record["sensors"].as_array().unwrap();
    let imu_record = sensors.iter().find(|s| s["name"] == "imu0").unwrap();
    let recorded: Vec<f64> = imu_record["written_T_BS"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let recorded: [f64; 16] = recorded.try_into().unwrap();
    let recorded = Pose::from_row_major(&recorded);
    assert!(imu.rotation.angle_between(recorded.rotation) < 1e-9);
    let angle = imu
        .rotation
        .angle_between(Pose::IDENTITY.rotation)
        .to_degrees();
    assert!(angle > 0.01 && angle < 4.0, "{angle}°");
    assert_eq!(imu_record["true_T_BS"], imu_record["nominal_T_BS"]);

    // ORB-SLAM3's settings carry the written calibration.
    let settings = std::fs::read_to_string(written.join("orbslam3_stereo_inertial.yaml")).unwrap();
    let t_c1_c2 = opencv_matrix(&settings, "Stereo.T_c1_c2");
    assert!(
        (t_c1_c2[3] - (NOMINAL_BASELINE_M + delta)).abs() < 1e-6,
        "{t_c1_c2:?}"
    );
    let t_b_c1 = opencv_matrix(&settings, "IMU.T_b_c1");
    let expected = imu.inverse().compose(&cam0).to_row_major();
    for (got, want) in t_b_c1.iter().zip(expected) {
        assert!(
            (got - want).abs() < 1e-6,
            "IMU.T_b_c1 {t_b_c1:?} vs {expected:?}"
        );
    }
}

/// The 16 numbers of `name: !!opencv-matrix … data: [ … ]`.
fn opencv_matrix(text: &str, name: &str) -> Vec<f64> {
    let start = text.find(&format!("{name}: !!opencv-matrix")).unwrap();
    let data = &text[start..];
    let open = data.find("data: [").unwrap() + "data: [".len();
    let close = data[open..].find(']').unwrap() + open;
    let values: Vec<f64> = data[open..close]
        .split(',')
        .map(|v| v.trim().parse().unwrap())
        .collect();
    assert_eq!(values.len(), 16, "{name}");
    values
}

#[test]
fn dynamic_baseline_moves_cam1_on_every_frame_and_records_each_draw() {
    let ws = Workspace::new();
    render(&ws, "clean", "stereo", None);
    let spec = format!("baseline:{BASELINE_SIGMA}@dynamic");
    render(&ws, "dynamic", "stereo", Some(&spec));
    let (clean, dynamic) = (ws.path("clean"), ws.path("dynamic"));
    let record = calibration_record(&dynamic);
    assert_eq!(record["baseline_mode"], "dynamic");
    assert_eq!(record["per_frame"], "calibration_per_frame.csv");
    let csv = std::fs::read_to_string(dynamic.join("calibration_per_frame.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("frame,t_ns,baseline_offset_m,baseline_true_m")
    );
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    let cam1 = frames(&dynamic, "cam1");
    assert_eq!(rows.len(), cam1.len());
    let offsets: Vec<f64> = rows.iter().map(|r| r[2].parse().unwrap()).collect();
    assert_ne!(offsets[0], offsets[1], "a new draw on every frame");
    for ((row, offset), frame) in rows.iter().zip(&offsets).zip(&cam1) {
        assert_eq!(
            format!("{}.png", row[1]),
            frame.file_name().unwrap().to_string_lossy()
        );
        let true_m: f64 = row[3].parse().unwrap();
        assert!((true_m - (NOMINAL_BASELINE_M + offset)).abs() < 1e-9);
    }
    // Each frame's disparity follows its own draw.
    let left = frames(&clean, "cam0");
    let nominal_right = frames(&clean, "cam1");
    for (k, offset) in offsets.iter().enumerate() {
        let (ratio, _) =
            median_disparity_ratio(&grey(&left[k]), &grey(&nominal_right[k]), &grey(&cam1[k]));
        let expected = (NOMINAL_BASELINE_M + offset) / NOMINAL_BASELINE_M;
        assert!(
            (ratio / expected - 1.0).abs() < RATIO_TOLERANCE,
            "frame {k}: disparity ratio {ratio}, expected {expected}"
        );
    }
    assert!(same_bytes(
        &clean.join("mav0/cam1/sensor.yaml"),
        &dynamic.join("mav0/cam1/sensor.yaml")
    ));
}

/// `imu0/data.csv` rows: gyroscope and accelerometer readings.
fn imu_readings(root: &Path) -> Vec<[f64; 6]> {
    let csv = std::fs::read_to_string(root.join("mav0/imu0/data.csv")).unwrap();
    csv.lines()
        .skip(1)
        .map(|line| {
            let values: Vec<f64> = line
                .split(',')
                .skip(1)
                .map(|v| v.trim().parse().unwrap())
                .collect();
            values.try_into().unwrap()
        })
        .collect()
}

#[test]
fn an_imu_turned_in_rendered_mode_reads_in_its_turned_frame_and_the_files_stay_nominal() {
    let ws = Workspace::new();
    render(&ws, "clean", "stereo-imu", None);
    render(&ws, "turned", "stereo-imu", Some("imu0:extrinsic_rot:2"));
    let (clean, turned) = (ws.path("clean"), ws.path("turned"));
    for file in ["mav0/imu0/sensor.yaml", "orbslam3_stereo_inertial.yaml"] {
        assert!(same_bytes(&clean.join(file), &turned.join(file)), "{file}");
    }
    for camera in ["cam0", "cam1"] {
        for (a, b) in frames(&clean, camera).iter().zip(frames(&turned, camera)) {
            assert!(same_bytes(a, &b), "{} changed", b.display());
        }
    }
    let record = calibration_record(&turned);
    let imu = record["sensors"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "imu0")
        .unwrap();
    assert_eq!(imu["written_T_BS"], imu["nominal_T_BS"]);
    let t: Vec<f64> = imu["true_T_BS"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let t: [f64; 16] = t.try_into().unwrap();
    let body_from_imu = Pose::from_row_major(&t);
    assert!(
        body_from_imu
            .rotation
            .angle_between(Pose::IDENTITY.rotation)
            > 0.01f64.to_radians()
    );

    // The turned IMU measures the nominal one's vectors in its own axes (same noise draws, added
    // in the IMU's frame): rotating the nominal readings explains the difference.
    let imu_from_body = Pose::new(body_from_imu.rotation.inverse(), Default::default());
    let (nominal, moved) = (imu_readings(&clean), imu_readings(&turned));
    assert_eq!(nominal.len(), moved.len());
    let (mut raw, mut explained) = (0.0f64, 0.0f64);
    for (n, m) in nominal.iter().zip(&moved) {
        let accel_n = imu_from_body
            .transform_point([n[3], n[4], n[5]].into())
            .to_array();
        let diff = |a: [f64; 3]| {
            ((a[0] - m[3]).powi(2) + (a[1] - m[4]).powi(2) + (a[2] - m[5]).powi(2)).sqrt()
        };
        raw = raw.max(diff([n[3], n[4], n[5]]));
        explained = explained.max(diff(accel_n));
    }
    assert!(
        raw > 0.1,
        "turning the IMU must change its readings: {raw} m/s²"
    );
    assert!(
        explained < 0.1 * raw,
        "rotated nominal readings differ by {explained} m/s², unrotated by {raw}"
    );
}

/// `calibration_per_frame.csv` of `root`: its header, and each column's values by frame.
fn per_frame_columns(root: &Path) -> (String, Vec<Vec<f64>>) {
    let csv = std::fs::read_to_string(root.join("calibration_per_frame.csv")).unwrap();
    let mut lines = csv.lines();
    let header = lines.next().unwrap().to_string();
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let columns = (0..rows[0].len())
        .map(|c| rows.iter().map(|r| r[c]).collect())
        .collect();
    (header, columns)
}

/// The three columns `{prefix}_x{suffix}`, `…_y…`, `…_z…` on frame `k`.
fn per_frame_vector(
    header: &str,
    columns: &[Vec<f64>],
    prefix: &str,
    unit: &str,
    k: usize,
) -> DVec3 {
    let at = |axis: &str| {
        let name = format!("{prefix}_{axis}_{unit}");
        let c = header
            .split(',')
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no {name} in {header}"));
        columns[c][k]
    };
    DVec3::new(at("x"), at("y"), at("z"))
}

/// Mean absolute grey difference between `moved` and `nominal` as seen by a camera turned by
/// `nominal_from_moved` about its centre: moved pixel x' shows what nominal pixel K·R·K⁻¹·x'
/// shows (bilinear), over the pixels whose source lies 2 px inside the nominal image.
fn turned_view_error(
    nominal: &image::GrayImage,
    moved: &image::GrayImage,
    k: &Intrinsics,
    nominal_from_moved: DQuat,
) -> f64 {
    let at = |x: u32, y: u32| nominal.get_pixel(x, y)[0] as f64;
    let (mut sum, mut count) = (0.0, 0usize);
    for y in 0..moved.height() {
        for x in 0..moved.width() {
            let ray = DVec3::new((x as f64 - k.cx) / k.fx, (y as f64 - k.cy) / k.fy, 1.0);
            let d = nominal_from_moved * ray;
            let (u, v) = (k.fx * d.x / d.z + k.cx, k.fy * d.y / d.z + k.cy);
            if d.z <= 0.0
                || u < 2.0
                || v < 2.0
                || u > k.width as f64 - 3.0
                || v > k.height as f64 - 3.0
            {
                continue;
            }
            let (x0, y0) = (u.floor() as u32, v.floor() as u32);
            let (fx, fy) = (u - x0 as f64, v - y0 as f64);
            let sample = (1.0 - fy) * ((1.0 - fx) * at(x0, y0) + fx * at(x0 + 1, y0))
                + fy * ((1.0 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
            sum += (sample - moved.get_pixel(x, y)[0] as f64).abs();
            count += 1;
        }
    }
    assert!(count > 1000, "{count} pixels compared");
    sum / count as f64
}

#[test]
fn dynamic_extrinsic_rot_turns_cam0_on_every_frame_by_the_listed_rotation() {
    let ws = Workspace::new();
    render(&ws, "clean", "stereo", None);
    render(
        &ws,
        "shaken",
        "stereo",
        Some("cam0:extrinsic_rot:1@dynamic"),
    );
    let (clean, shaken) = (ws.path("clean"), ws.path("shaken"));
    let record = calibration_record(&shaken);
    assert_eq!(
        record["dynamic"],
        serde_json::json!(["cam0:extrinsic_rot:1@dynamic"])
    );
    assert_eq!(record["per_frame"], "calibration_per_frame.csv");
    // cam1 is not addressed and the files state the nominal rig.
    for (a, b) in frames(&clean, "cam1").iter().zip(frames(&shaken, "cam1")) {
        assert!(same_bytes(a, &b), "{} changed", b.display());
    }
    for file in ["mav0/cam0/sensor.yaml", "orbslam3_stereo.yaml"] {
        assert!(same_bytes(&clean.join(file), &shaken.join(file)), "{file}");
    }

    let (header, columns) = per_frame_columns(&shaken);
    assert_eq!(
        header,
        "frame,t_ns,baseline_true_m,cam0_rot_x_deg,cam0_rot_y_deg,cam0_rot_z_deg,cam0_trans_x_m,cam0_trans_y_m,cam0_trans_z_m"
    );
    let cam0 = frames(&shaken, "cam0");
    assert_eq!(columns[1].len(), cam0.len());
    let intrinsics = read_euroc(&shaken).unwrap().cameras[0].camera.intrinsics;
    let rotations: Vec<DQuat> = (0..cam0.len())
        .map(|k| {
            assert_eq!(
                format!("{}.png", columns[1][k]),
                cam0[k].file_name().unwrap().to_string_lossy()
            );
            let degrees = per_frame_vector(&header, &columns, "cam0_rot", "deg", k);
            assert_eq!(
                per_frame_vector(&header, &columns, "cam0_trans", "m", k),
                DVec3::ZERO
            );
            DQuat::from_scaled_axis(degrees * std::f64::consts::PI / 180.0)
        })
        .collect();
    assert_ne!(rotations[0], rotations[1], "a new draw on every frame");
    // Each frame is the nominal one seen through its own listed turn, and not through the
    // nominal mount or another frame's turn.
    let nominal = frames(&clean, "cam0");
    for (k, rotation) in rotations.iter().enumerate() {
        let (n, m) = (grey(&nominal[k]), grey(&cam0[k]));
        let listed = turned_view_error(&n, &m, &intrinsics, *rotation);
        let unturned = turned_view_error(&n, &m, &intrinsics, DQuat::IDENTITY);
        let other = turned_view_error(&n, &m, &intrinsics, rotations[(k + 1) % rotations.len()]);
        assert!(
            listed < 3.0 && listed < 0.2 * unturned.min(other),
            "frame {k}: grey error {listed} with the listed turn, {unturned} without, {other} with another frame's"
        );
    }
}

/// Median over pixels of |depth the moved camera sees − depth predicted for it|, predicting from
/// the nominal depth image with the moved camera shifted by `shift` (its own frame) from the
/// nominal one: nominal pixel x at depth Z is the point P = Z·K⁻¹x, which the moved camera sees
/// at K·(P − shift) with depth (P − shift)_z (moved depth read bilinearly where its four pixels
/// have depth).
fn shifted_depth_error(
    nominal: &DepthImage,
    moved: &DepthImage,
    k: &Intrinsics,
    shift: DVec3,
) -> f64 {
    let at = |img: &DepthImage, x: u32, y: u32| img.data[(y * img.width + x) as usize] as f64;
    let mut residuals = Vec::new();
    for y in 0..nominal.height {
        for x in 0..nominal.width {
            let z = at(nominal, x, y);
            if z <= 0.0 {
                continue;
            }
            let p = DVec3::new(
                (x as f64 - k.cx) / k.fx * z,
                (y as f64 - k.cy) / k.fy * z,
                z,
            ) - shift;
            let (u, v) = (k.fx * p.x / p.z + k.cx, k.fy * p.y / p.z + k.cy);
            if p.z <= 0.0
                || u < 0.0
                || v < 0.0
                || u >= k.width as f64 - 1.0
                || v >= k.height as f64 - 1.0
            {
                continue;
            }
            let (x0, y0) = (u.floor() as u32, v.floor() as u32);
            let corners = [(x0, y0), (x0 + 1, y0), (x0, y0 + 1), (x0 + 1, y0 + 1)]
                .map(|(x, y)| at(moved, x, y));
            if corners.iter().any(|d| *d <= 0.0) {
                continue;
            }
            let (fx, fy) = (u - x0 as f64, v - y0 as f64);
            let seen = (1.0 - fy) * ((1.0 - fx) * corners[0] + fx * corners[1])
                + fy * ((1.0 - fx) * corners[2] + fx * corners[3]);
            residuals.push((seen - p.z).abs());
        }
    }
    assert!(
        residuals.len() > 1000,
        "{} pixels compared",
        residuals.len()
    );
    residuals.sort_by(f64::total_cmp);
    residuals[residuals.len() / 2]
}

#[test]
fn dynamic_extrinsic_trans_shifts_the_rgbd_imu_camera_on_every_frame_by_the_listed_offset() {
    let ws = Workspace::new();
    let args = [
        "--frames",
        "7",
        "--camera",
        "320,240,260,260,159.5,119.5",
        "--rate",
        "30",
        "--rig",
        "rgbd-imu",
        "--format",
        "tum",
    ];
    ws.render_room0("clean", &args, None);
    ws.render_room0("shaken", &args, Some("cam0:extrinsic_trans:0.05@dynamic"));
    let (clean, shaken) = (ws.path("clean"), ws.path("shaken"));
    let record = calibration_record(&shaken);
    assert_eq!(
        record["dynamic"],
        serde_json::json!(["cam0:extrinsic_trans:0.05@dynamic"])
    );
    // The IMU and every calibration file are nominal.
    for file in [
        "imu0/data.csv",
        "imu0/sensor.yaml",
        "orbslam3_rgbd_inertial.yaml",
    ] {
        assert!(same_bytes(&clean.join(file), &shaken.join(file)), "{file}");
    }

    let (header, columns) = per_frame_columns(&shaken);
    assert!(header.starts_with("frame,t_ns,cam0_rot_x_deg,"), "{header}");
    let read = |root: &Path| read_dataset(root, &DatasetOverrides::default()).unwrap();
    let (nominal, moved) = (read(&clean), read(&shaken));
    assert_eq!(columns[1].len(), moved.frames.len());
    let shifts: Vec<DVec3> = (0..moved.frames.len())
        .map(|k| {
            assert!((columns[1][k] * 1e-9 - moved.frames[k].rgb_time).abs() < 1e-6);
            assert_eq!(
                per_frame_vector(&header, &columns, "cam0_rot", "deg", k),
                DVec3::ZERO
            );
            per_frame_vector(&header, &columns, "cam0_trans", "m", k)
        })
        .collect();
    assert_ne!(shifts[0], shifts[1], "a new draw on every frame");

    // groundtruth.txt is the camera as it was on each frame: the nominal pose shifted by the
    // listed offset in the camera's frame.
    let shifted: Vec<Pose> = nominal
        .ground_truth
        .as_ref()
        .unwrap()
        .poses
        .iter()
        .zip(&shifts)
        .map(|(pose, shift)| pose.compose(&Pose::new(DQuat::IDENTITY, *shift)))
        .collect();
    assert_poses_close(&moved.ground_truth.as_ref().unwrap().poses, &shifted, 1e-5);

    // Each frame's depth is what the nominal geometry looks like from the listed shift, and not
    // from the nominal mount or another frame's shift.
    let depth = |ds: &rslam_core::dataset::SourceDataset, k: usize| {
        decode_depth_png(
            ds.frames[k].depth.as_ref().unwrap(),
            DatasetFormat::Tum.depth_scale(),
        )
        .unwrap()
    };
    for (k, shift) in shifts.iter().enumerate() {
        let (n, m) = (depth(&nominal, k), depth(&moved, k));
        let listed = shifted_depth_error(&n, &m, &moved.intrinsics, *shift);
        let unshifted = shifted_depth_error(&n, &m, &moved.intrinsics, DVec3::ZERO);
        let other = shifted_depth_error(&n, &m, &moved.intrinsics, shifts[(k + 1) % shifts.len()]);
        assert!(
            listed < 1e-3 && listed < 0.1 * unshifted.min(other),
            "frame {k}: median depth error {listed} m with the listed shift, {unshifted} without, {other} with another frame's"
        );
    }
}
