//! `rslam render --rig rgbd` (the render without `--rig`, byte for byte) and `--rig rgbd-imu
//! --format tum` (the TUM layout plus the IMU as EuRoC has it and ORB-SLAM3's RGB-D-inertial
//! settings), read back with rslam's reader and a small parser of the files' own.

use std::path::Path;

use rslam_core::dataset::euroc::{GROUND_TRUTH_HEADER, IMU_HEADER};
use rslam_core::dataset::{read_dataset, Checksums, DatasetFormat, DatasetOverrides};
use rslam_core::trajectory_io::{read_trajectory, TrajectoryFormat};
use rslam_core::{Intrinsics, Pose};

use crate::dataset_check::{
    assert_poses_close, assert_same_files, lines, manifest, tree, tum_trajectory,
};
use crate::harness::Workspace;
use crate::imu_items;
use crate::render::SMALL_CAMERA;

fn small_render(format: &str, extra: &[&str]) -> Vec<String> {
    let mut args: Vec<String> = [
        "render",
        "--scene",
        "room0",
        "--frames",
        "7",
        "--camera",
        SMALL_CAMERA,
        "--rate",
        "30",
        "--format",
        format,
        "--seed",
        "3",
        "--out",
        "ds",
    ]
    .map(String::from)
    .to_vec();
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

fn run(ws: &Workspace, args: &[String]) -> crate::harness::Run {
    ws.rslam(&args.iter().map(String::as_str).collect::<Vec<_>>())
}

/// `--rig rgbd` is the same job as no `--rig`: every file is the same (the manifest but for the
/// command line it records), and each run finds the other's output complete.
#[test]
fn rgbd_rig_writes_the_bytes_of_a_render_without_rig() {
    for format in ["replica", "tum"] {
        let plain = Workspace::new();
        let extra = ["--perturb", "gaussian_noise:2,depth_missing:1"];
        run(&plain, &small_render(format, &extra)).success();
        let rigged = Workspace::new();
        let with_rig = small_render(format, &[&extra[..], &["--rig", "rgbd"]].concat());
        run(&rigged, &with_rig).success();

        let (a, b) = (tree(&plain.path("ds")), tree(&rigged.path("ds")));
        assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>());
        for (name, bytes) in &a {
            if name != "rslam.json" {
                assert!(bytes == &b[name], "{format}: {name} differs");
            }
        }
        let (ma, mb) = (manifest(&plain.path("ds")), manifest(&rigged.path("ds")));
        assert_ne!(ma.command, mb.command, "the typed command is recorded");
        assert_eq!(ma.job(), mb.job(), "{format}");
        assert_eq!(ma.content_digest, mb.content_digest);

        let again = run(&plain, &with_rig);
        again.success();
        assert!(
            again.stderr().contains("already complete"),
            "{}",
            again.stderr()
        );
    }
}

/// The 16 numbers of `key: !!opencv-matrix … data: [...]` in an ORB-SLAM3 settings file.
fn opencv_matrix(text: &str, key: &str) -> [f64; 16] {
    let at = text
        .find(&format!("{key}:"))
        .unwrap_or_else(|| panic!("no {key}"));
    let start = at + text[at..].find('[').unwrap();
    let end = start + text[start..].find(']').unwrap();
    let values: Vec<f64> = text[start + 1..end]
        .split(',')
        .map(|v| v.trim().parse().unwrap())
        .collect();
    values.try_into().unwrap()
}

/// The number after `key:` at the start of a line of a YAML file (a comment may follow it).
fn setting(text: &str, key: &str) -> f64 {
    let line = text
        .lines()
        .find(|l| l.starts_with(&format!("{key}:")))
        .unwrap_or_else(|| panic!("no {key} in\n{text}"));
    let value = line[key.len() + 1..].split_whitespace().next().unwrap();
    value.parse().unwrap_or_else(|_| panic!("{key}: {value}"))
}

/// Rows of a EuRoC data.csv after its header (which must be `header`), split at commas.
fn csv_rows(path: &Path, header: &str) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut rows = text.lines();
    assert_eq!(rows.next(), Some(header), "{}", path.display());
    rows.map(|l| l.split(',').map(|f| f.trim().to_string()).collect())
        .collect()
}

const RGBD_IMU: [&str; 2] = ["--rig", "rgbd-imu"];

#[test]
fn rgbd_imu_writes_tum_frames_a_200_hz_imu_and_consistent_calibration() {
    let ws = Workspace::new();
    let args = small_render("tum", &RGBD_IMU);
    run(&ws, &args).success();
    let root = ws.path("ds");

    // The TUM layout as rslam reads it: the camera given, 7 path poses at 30 Hz → the spline is
    // valid from the second pose's time for 4/30 s, which the IMU covers to 0.130 s: 4 frames,
    // 1/30 s apart (the fifth, at 0.133 s, would come after the IMU's last sample).
    let dataset = read_dataset(&root, &DatasetOverrides::default()).unwrap();
    assert_eq!(dataset.format, DatasetFormat::Tum);
    assert_eq!(dataset.intrinsics, Intrinsics::parse(SMALL_CAMERA).unwrap());
    assert_eq!(dataset.rate_hz, 30.0);
    let stamps: Vec<f64> = dataset.frames.iter().map(|f| f.rgb_time).collect();
    assert_eq!(stamps.len(), 4);
    for (k, t) in stamps.iter().enumerate() {
        assert!((t - (k + 1) as f64 / 30.0).abs() < 1e-6, "{stamps:?}");
        assert!(dataset.frames[k].depth.as_ref().unwrap().is_file());
    }
    for file in ["rgb.txt", "depth.txt", "associations.txt", "orbslam3.yaml"] {
        assert!(root.join(file).is_file(), "{file}");
    }

    // imu0/data.csv: 200 Hz, nanosecond stamps, covering every frame.
    let imu: Vec<u64> = csv_rows(&root.join("imu0/data.csv"), IMU_HEADER)
        .iter()
        .map(|row| {
            assert_eq!(row.len(), 7, "{row:?}");
            row[0].parse().unwrap()
        })
        .collect();
    assert_eq!(imu.len(), 27, "0.13 s at 200 Hz, both ends");
    assert!(imu.windows(2).all(|w| w[1] - w[0] == 5_000_000), "{imu:?}");
    let (first, last) = (imu[0] as f64 * 1e-9, imu[26] as f64 * 1e-9);
    // (rgb.txt keeps 6 decimals)
    assert!(first <= stamps[0] + 1e-6 && last >= stamps[3] - 1e-6);
    let sensor = std::fs::read_to_string(root.join("imu0/sensor.yaml")).unwrap();
    assert_eq!(setting(&sensor, "rate_hz"), 200.0);
    assert_eq!(setting(&sensor, "gyroscope_noise_density"), 2.44e-4);
    assert_eq!(setting(&sensor, "accelerometer_random_walk"), 1e-4);

    // groundtruth.txt (the camera) is the body's ground truth composed with the T_b_c1 written
    // for ORB-SLAM3, wherever a frame and an IMU sample share a time (every third frame).
    let settings = std::fs::read_to_string(root.join("orbslam3_rgbd_inertial.yaml")).unwrap();
    let body_from_camera = Pose::from_row_major(&opencv_matrix(&settings, "IMU.T_b_c1"));
    let body_csv = root.join("state_groundtruth_estimate0/data.csv");
    let rows = csv_rows(&body_csv, GROUND_TRUTH_HEADER);
    assert!(rows.iter().all(|row| row.len() == 17));
    let body = read_trajectory(&body_csv, Some(TrajectoryFormat::Euroc))
        .unwrap()
        .trajectory;
    assert_eq!(body.len(), imu.len());
    let camera = tum_trajectory(&root);
    let (mut from_body, mut written) = (Vec::new(), Vec::new());
    for (t, pose) in camera.timestamps.iter().zip(&camera.poses) {
        let at = body.timestamps.iter().position(|tb| (tb - t).abs() < 1e-6);
        if let Some(i) = at {
            from_body.push(body.poses[i].compose(&body_from_camera));
            written.push(*pose);
        }
    }
    assert_eq!(written.len(), 2, "frames 0 and 3 fall on IMU samples");
    assert_poses_close(&written, &from_body, 1e-6);
    // the camera is not at the body's origin: the check would catch a missing extrinsic
    assert!((body_from_camera.translation.length() - 0.0238).abs() < 1e-3);

    // ORB-SLAM3 RGB-D-inertial: the RGB-D file's keys, then the IMU's as imu0/sensor.yaml says.
    let rgbd = std::fs::read_to_string(root.join("orbslam3.yaml")).unwrap();
    assert!(settings.starts_with(&rgbd), "{settings}");
    for (key, want) in [
        ("IMU.NoiseGyro", 2.44e-4),
        ("IMU.NoiseAcc", 1.47e-3),
        ("IMU.GyroWalk", 1e-6),
        ("IMU.AccWalk", 1e-4),
        ("IMU.Frequency", 200.0),
        ("IMU.InsertKFsWhenLost", 0.0),
        ("Camera.fps", 30.0),
        ("RGBD.DepthMapFactor", 5000.0),
    ] {
        assert_eq!(setting(&settings, key), want, "{key}");
    }

    let again = run(&ws, &args);
    again.success();
    assert!(again.stderr().contains("already complete"));
}

/// `cam_imu_offset:MS` moves the frames' stamps (rgb.txt, depth.txt), not the IMU's or the
/// ground truth's, which keep the true capture times.
#[test]
fn cam_imu_offset_moves_the_frame_stamps_of_rgbd_imu_only() {
    let clean = Workspace::new();
    run(&clean, &small_render("tum", &RGBD_IMU)).success();
    let shifted = Workspace::new();
    let offset = [&RGBD_IMU[..], &["--perturb", "cam_imu_offset:2.5"]].concat();
    run(&shifted, &small_render("tum", &offset)).success();
    let stamps = |ws: &Workspace, file: &str| -> Vec<f64> {
        lines(&ws.path("ds").join(file))
            .iter()
            .map(|l| l.split_whitespace().next().unwrap().parse().unwrap())
            .collect()
    };
    for file in ["rgb.txt", "depth.txt"] {
        let (a, b) = (stamps(&clean, file), stamps(&shifted, file));
        assert_eq!(a.len(), b.len());
        assert!(a.iter().zip(&b).all(|(a, b)| (b - a - 0.0025).abs() < 2e-6));
    }
    assert_eq!(
        stamps(&clean, "groundtruth.txt"),
        stamps(&shifted, "groundtruth.txt")
    );
    assert_same_files(
        &clean.path("ds"),
        &shifted.path("ds"),
        &["imu0/data.csv", "state_groundtruth_estimate0/data.csv"],
    );
}

/// `rslam perturb --input` of an `rgbd-imu` output keeps it RGB-D-inertial: its frames are
/// corrupted, its IMU, body ground truth and settings copied byte for byte and listed in the
/// checksums; `fast` and `cam_imu_offset` (they re-stamp the frames) are refused naming imu0/.
#[test]
fn perturbing_an_rgbd_imu_output_keeps_its_inertial_files() {
    let ws = Workspace::new();
    run(&ws, &small_render("tum", &RGBD_IMU)).success();
    let perturb = |out: &str, spec: &str| {
        ws.rslam(&["perturb", "--input", "ds", "--out", out, "--perturb", spec])
    };
    perturb("fog", "fog:2,misalign:1").success();
    let listed: Vec<String> = Checksums::read(&ws.path("fog"))
        .unwrap()
        .paths()
        .map(str::to_string)
        .collect();
    let inertial = [
        "imu0/data.csv",
        "imu0/sensor.yaml",
        "state_groundtruth_estimate0/data.csv",
        "orbslam3_rgbd_inertial.yaml",
    ];
    assert_same_files(&ws.path("ds"), &ws.path("fog"), &inertial);
    for file in inertial {
        assert!(listed.iter().any(|p| p == file), "{file} not in {listed:?}");
    }
    assert_eq!(
        lines(&ws.path("ds/rgb.txt")),
        lines(&ws.path("fog/rgb.txt")),
        "frames keep their stamps, so the IMU still matches them"
    );
    ws.rslam(&["verify", "fog"]).success();

    for (spec, item) in [
        ("fast:2", "'fast:2'"),
        ("imu_noise:2,cam_imu_offset:3", "'cam_imu_offset:3'"),
    ] {
        let err = perturb("refused", spec).fails_with(2, &[item, "imu0/"]);
        let said: Vec<&str> = err.lines().filter(|l| !l.starts_with("adapter:")).collect();
        assert!(said.len() == 1 && said[0].starts_with("error:"), "{err}");
    }
    assert!(!ws.path("refused").exists(), "nothing written");
}

/// The IMU stream items reach an `rgbd-imu` output's recorded IMU as they reach a EuRoC one:
/// a bias step shows in the readings and in the ground truth's true biases from the recorded
/// time on, by the recorded vectors; the calibration files and the frames' stamps stay.
#[test]
fn a_bias_step_reaches_the_imu_and_true_biases_of_an_rgbd_imu_output() {
    let ws = Workspace::new();
    let mut args = small_render("tum", &RGBD_IMU);
    args[4] = "40".into(); // --frames
    run(&ws, &args).success();
    ws.rslam(&[
        "perturb",
        "--input",
        "ds",
        "--out",
        "step",
        "--perturb",
        "imu_bias_step:0.02/0.3",
    ])
    .success();
    let (input, out) = (ws.path("ds"), ws.path("step"));
    assert_same_files(
        &input,
        &out,
        &["imu0/sensor.yaml", "orbslam3_rgbd_inertial.yaml"],
    );
    assert_eq!(lines(&input.join("rgb.txt")), lines(&out.join("rgb.txt")));
    ws.rslam(&["verify", "step"]).success();

    let step = &imu_items::manifest(&out)["extra"]["imu_perturbation"]["bias_step"];
    let at_ns = step["at_ns"].as_u64().unwrap();
    let (gyro, accel) = (
        imu_items::vector(&step["gyroscope"]),
        imu_items::vector(&step["accelerometer"]),
    );
    // (stamp, first column of the three gyroscope and three accelerometer values)
    for (file, gyro_column) in [
        ("imu0/data.csv", 0),
        ("state_groundtruth_estimate0/data.csv", 10),
    ] {
        let (before, after) = (
            imu_items::rows(&input.join(file)),
            imu_items::rows(&out.join(file)),
        );
        assert_eq!(before.len(), after.len(), "{file}");
        let mut stepped = 0;
        for ((t, b), (t_out, a)) in before.iter().zip(&after) {
            assert_eq!(t, t_out, "{file}: stamps stay");
            let on = *t >= at_ns;
            stepped += usize::from(on);
            for axis in 0..3 {
                let (g, c) = (gyro_column + axis, gyro_column + 3 + axis);
                let want = |v: [f64; 3]| if on { v[axis] } else { 0.0 };
                assert!((a[g] - b[g] - want(gyro)).abs() < 1e-9, "{file} {t}");
                assert!((a[c] - b[c] - want(accel)).abs() < 1e-9, "{file} {t}");
            }
        }
        assert!(stepped > 0 && stepped < before.len(), "{file}: {stepped}");
    }
}

#[test]
fn rgbd_rig_flags_fail_with_one_line_errors() {
    let ws = Workspace::new();
    let base = ["render", "--scene", "room0", "--frames", "4", "--out", "x"];
    let fail = |extra: &[&str], fragments: &[&str]| {
        let err = ws
            .rslam(&[&base[..], extra].concat())
            .fails_with(2, fragments);
        // refused before anything is written; a refusal after the GPU opened follows its line
        let said: Vec<&str> = err.lines().filter(|l| !l.starts_with("adapter:")).collect();
        assert!(said.len() == 1 && said[0].starts_with("error:"), "{err}");
    };
    fail(&["--rig", "rgbd-imu"], &["--rig rgbd-imu", "--format tum"]);
    fail(
        &["--rig", "rgbd-imu", "--format", "euroc"],
        &["--format euroc", "stereo"],
    );
    fail(&["--rig", "rgbd", "--format", "euroc"], &["--format euroc"]);
    fail(
        &[
            "--rig",
            "rgbd-imu",
            "--format",
            "tum",
            "--perturb",
            "distortion:equidistant(0.08,-0.03,0.01,-0.002)",
        ],
        &[
            "'distortion:equidistant",
            "the rgbd-imu rig does not support a lens yet",
        ],
    );
    fail(
        &["--rig", "rgbd", "--perturb", "imu_noise:2"],
        &["'imu_noise:2'", "IMU"],
    );
    assert!(!ws.path("x").exists(), "nothing written");
}

/// A killed `rgbd-imu` render resumes frame by frame to the bytes of an uninterrupted one, IMU
/// files and settings included.
#[test]
fn a_killed_rgbd_imu_render_resumes_to_the_same_bytes() {
    let mut args = small_render("tum", &RGBD_IMU);
    args[4] = "300".into(); // --frames
    args.extend(["--perturb", "gaussian_noise:2,imu_noise:2"].map(String::from));
    let whole = Workspace::new();
    run(&whole, &args).success();
    let killed = Workspace::new();
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    crate::resume::kill_mid_run(&killed, &refs, "ds", "rgb", "");
    let resumed = run(&killed, &args);
    resumed.success();
    assert!(resumed.stderr().contains("resumed"), "{}", resumed.stderr());
    crate::dataset_check::assert_same_tree(&whole.path("ds"), &killed.path("ds"));
}
