//! `rslam perturb --input <EuRoC folder>`: a published-style sequence (two grey cameras, real
//! 19-digit nanosecond stamps, IMU and ground truth) copied with its frames corrupted, and the
//! one-line refusal of items that are not image corruptions.

use std::path::Path;

use crate::dataset_check::assert_same_files;
use crate::harness::{sorted_names, Workspace};

/// MH_01_easy's first two cam0 stamps (multiples of 256 ns, as published) and one of any
/// nanosecond (TUM-VI's stamps are), which f64 seconds could not hold.
pub(crate) const STAMPS: [u64; 3] = [
    1_403_636_579_763_555_584,
    1_403_636_579_813_555_456,
    1_403_636_579_863_555_555,
];
const WIDTH: u32 = 64;
const HEIGHT: u32 = 48;
/// gaussian_noise:3 must change the frames, yet leave them recognisable.
const PSNR_BELOW_DB: f64 = 40.0;
const PSNR_ABOVE_DB: f64 = 10.0;

/// cam0/sensor.yaml of MH_01_easy, resized to 64×48.
fn camera_yaml(name: &str) -> String {
    format!(
        "# General sensor definitions.
sensor_type: camera
comment: VI-Sensor {name} (MT9M034)

# Sensor extrinsics wrt. the body-frame.
T_BS:
  cols: 4
  rows: 4
  data: [0.0148655429818, -0.999880929698, 0.00414029679422, -0.0216401454975,
         0.999557249008, 0.0149672133247, 0.025715529948, -0.064676986768,
        -0.0257744366974, 0.00375618835797, 0.999660727178, 0.00981073058949,
         0.0, 0.0, 0.0, 1.0]

# Camera specific definitions.
rate_hz: 20
resolution: [{WIDTH}, {HEIGHT}]
camera_model: pinhole
intrinsics: [45.8654, 45.7296, 31.5, 23.5] #fu, fv, cu, cv
distortion_model: radial-tangential
distortion_coefficients: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]
"
    )
}

const IMU_YAML: &str = "#Default imu sensor yaml file
sensor_type: imu
comment: VI-Sensor IMU (ADIS16448)

# Sensor extrinsics wrt. the body-frame.
T_BS:
  cols: 4
  rows: 4
  data: [1.0, 0.0, 0.0, 0.0,
         0.0, 1.0, 0.0, 0.0,
         0.0, 0.0, 1.0, 0.0,
         0.0, 0.0, 0.0, 1.0]
rate_hz: 200

# inertial sensor noise model parameters (static)
gyroscope_noise_density: 1.6968e-04     # [ rad / s / sqrt(Hz) ]   ( gyro \"white noise\" )
gyroscope_random_walk: 1.9393e-05       # [ rad / s^2 / sqrt(Hz) ] ( gyro bias diffusion )
accelerometer_noise_density: 2.0000e-3  # [ m / s^2 / sqrt(Hz) ]   ( accel \"white noise\" )
accelerometer_random_walk: 3.0000e-3    # [ m / s^3 / sqrt(Hz) ].  ( accel bias diffusion )
";

const IMU_CSV: &str = "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\r
1403636579758555392,-0.099134701513277898,0.14730578886832138,0.02722713633111154,8.1476917083333333,-0.37592158333333331,-2.4026292499999999\r
1403636579763555584,-0.099134701513277898,0.14032447186034408,0.029321531433504733,8.033280791666666,-0.40861041666666664,-2.4026292499999999\r
";

const GT_CSV: &str = "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad s^-1], b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]
1403636580838555648,4.688319,-1.786938,0.783338,0.534108,-0.153029,-0.827383,-0.082152,-0.027876,0.033207,0.800006,-0.003172,0.021267,0.078502,-0.025266,0.136696,0.075593
1403636580843555328,4.688177,-1.786770,0.787350,0.534640,-0.152990,-0.826976,-0.082863,-0.029272,0.033992,0.804621,-0.003172,0.021267,0.078502,-0.025266,0.136696,0.075593
";

/// A textured grey frame, mid-range so that noise is not clipped away.
fn frame(camera: usize, j: usize) -> image::GrayImage {
    image::GrayImage::from_fn(WIDTH, HEIGHT, |x, y| {
        image::Luma([(60 + (x * 2 + y + 7 * j as u32 + 13 * camera as u32) % 120) as u8])
    })
}

/// Lays out a MH_01_easy-style sequence under `root` (no rslam manifest; `leica0/` and
/// `body.yaml`, which rslam does not read, as published).
pub(crate) fn write_published_style(root: &Path) {
    let mav = root.join("mav0");
    for (c, cam) in ["cam0", "cam1"].into_iter().enumerate() {
        let data = mav.join(cam).join("data");
        std::fs::create_dir_all(&data).unwrap();
        std::fs::write(mav.join(cam).join("sensor.yaml"), camera_yaml(cam)).unwrap();
        let mut csv = String::from("#timestamp [ns],filename\r\n");
        for (j, t) in STAMPS.iter().enumerate() {
            csv.push_str(&format!("{t},{t}.png\r\n"));
            frame(c, j).save(data.join(format!("{t}.png"))).unwrap();
        }
        std::fs::write(mav.join(cam).join("data.csv"), csv).unwrap();
    }
    std::fs::create_dir_all(mav.join("imu0")).unwrap();
    std::fs::write(mav.join("imu0/sensor.yaml"), IMU_YAML).unwrap();
    std::fs::write(mav.join("imu0/data.csv"), IMU_CSV).unwrap();
    std::fs::create_dir_all(mav.join("state_groundtruth_estimate0")).unwrap();
    std::fs::write(mav.join("state_groundtruth_estimate0/data.csv"), GT_CSV).unwrap();
    std::fs::create_dir_all(mav.join("leica0")).unwrap();
    std::fs::write(
        mav.join("body.yaml"),
        "comment: The body frame is the IMU frame\n",
    )
    .unwrap();
}

fn psnr_db(a: &[u8], b: &[u8]) -> f64 {
    assert_eq!(a.len(), b.len());
    let mse = a
        .iter()
        .zip(b)
        .map(|(&x, &y)| (x as f64 - y as f64).powi(2))
        .sum::<f64>()
        / a.len() as f64;
    10.0 * (255.0f64 * 255.0 / mse).log10()
}

#[test]
fn a_euroc_sequence_is_copied_with_its_frames_corrupted() {
    let ws = Workspace::new();
    write_published_style(&ws.path("MH_01_easy"));
    let args = [
        "perturb",
        "--input",
        "MH_01_easy",
        "--out",
        "out",
        "--perturb",
        "gaussian_noise:3",
    ];
    let run = ws.rslam(&args);
    run.success();
    let stderr = run.stderr();
    assert!(
        stderr.contains("wrote 3 frames from cam0, 3 frames from cam1, 2 IMU samples to out"),
        "{stderr}"
    );
    let (input, out) = (ws.path("MH_01_easy/mav0"), ws.path("out/mav0"));
    let cameras: Vec<String> = sorted_names(&out)
        .into_iter()
        .filter(|n| n.starts_with("cam"))
        .collect();
    assert_eq!(cameras, ["cam0", "cam1"]);

    let mut perturbed: Vec<Vec<Vec<u8>>> = Vec::new();
    for cam in &cameras {
        let names = sorted_names(&out.join(cam).join("data"));
        let expected: Vec<String> = STAMPS.iter().map(|t| format!("{t}.png")).collect();
        assert_eq!(names, expected, "{cam}: same stamps and file names");
        let csv = std::fs::read_to_string(out.join(cam).join("data.csv")).unwrap();
        let stamps: Vec<u64> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').next().unwrap().parse().unwrap())
            .collect();
        assert_eq!(stamps, STAMPS, "{cam}: data.csv keeps the nanoseconds");
        assert_eq!(
            std::fs::read(out.join(cam).join("sensor.yaml")).unwrap(),
            std::fs::read(input.join(cam).join("sensor.yaml")).unwrap(),
            "{cam}: sensor.yaml copied as it is"
        );
        let mut frames = Vec::new();
        for name in &names {
            let before = image::open(input.join(cam).join("data").join(name)).unwrap();
            let after = image::open(out.join(cam).join("data").join(name)).unwrap();
            assert_eq!(
                after.color(),
                image::ColorType::L8,
                "{cam}/{name}: still grey"
            );
            assert_eq!((after.width(), after.height()), (WIDTH, HEIGHT));
            let (before, after) = (
                before.into_luma8().into_raw(),
                after.into_luma8().into_raw(),
            );
            let psnr = psnr_db(&before, &after);
            assert!(
                psnr > PSNR_ABOVE_DB && psnr < PSNR_BELOW_DB,
                "{cam}/{name}: PSNR {psnr:.1} dB"
            );
            frames.push(after);
        }
        perturbed.push(frames);
    }
    // Per-camera seeds: the noise each camera received differs.
    let noise = |c: usize, j: usize| -> Vec<i16> {
        let clean = frame(c, j).into_raw();
        clean
            .iter()
            .zip(&perturbed[c][j])
            .map(|(&a, &b)| b as i16 - a as i16)
            .collect()
    };
    for j in 0..STAMPS.len() {
        assert_ne!(
            noise(0, j),
            noise(1, j),
            "frame {j}: same noise in cam0 and cam1"
        );
    }
    assert_same_files(
        &input,
        &out,
        &[
            "imu0/data.csv",
            "imu0/sensor.yaml",
            "state_groundtruth_estimate0/data.csv",
        ],
    );
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(ws.path("out/rslam.json")).unwrap()).unwrap();
    assert_eq!(manifest["source"], "MH_01_easy");
    assert_eq!(manifest["perturbation"], "gaussian_noise:3");
    assert_eq!(manifest["seed"], 0);
    assert!(ws.path("out/orbslam3_stereo_inertial.yaml").is_file());

    let verify = ws.rslam(&["verify", "out"]);
    assert!(verify.success().contains("out: ok"), "{}", verify.stdout());
    let again = ws.rslam(&args);
    again.success();
    assert!(
        again.stderr().contains("already complete"),
        "{}",
        again.stderr()
    );
}

#[test]
fn items_that_are_not_image_corruptions_and_other_folders_are_refused() {
    let ws = Workspace::new();
    write_published_style(&ws.path("seq"));
    for (spec, item, reason) in [
        (
            "fog:2,depth_noise:3",
            "depth_noise:3",
            "depth corruptions need depth, and a EuRoC dataset's cameras have no depth stream",
        ),
        (
            "fast:2",
            "fast:2",
            "fast plays the sequence faster than it was captured, and a recorded EuRoC dataset keeps each frame's stamp",
        ),
    ] {
        let err = ws
            .rslam(&[
                "perturb",
                "--input",
                "seq/mav0",
                "--out",
                "x",
                "--perturb",
                spec,
            ])
            .fails_with(
                2,
                &[&format!("--perturb item '{item}': {reason}")],
            );
        assert_eq!(err.lines().count(), 1, "{err}");
    }
    let err = ws
        .rslam(&["perturb", "--input", "seq", "--out", "x", "--perturb", "baseline:0.01"])
        .fails_with(
            2,
            &["'baseline:0.01': a recorded dataset cannot be re-rendered with a moved sensor; perturb its written calibration instead: baseline:0.01@calibration"],
        );
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(!ws.path("x").exists());
    ws.write("mine/notes.txt", "mine");
    let err = ws
        .rslam(&[
            "perturb",
            "--input",
            "seq",
            "--out",
            "mine",
            "--perturb",
            "fog:1",
        ])
        .fails_with(2, &["holds no rslam output"]);
    assert_eq!(
        err.lines().filter(|l| l.starts_with("error")).count(),
        1,
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(ws.path("mine/notes.txt")).unwrap(),
        "mine"
    );
}

#[test]
fn calibration_items_rewrite_the_written_calibration_and_per_camera_items_one_camera() {
    let ws = Workspace::new();
    write_published_style(&ws.path("MH_01_easy"));
    let spec =
        "cam1:gaussian_noise:3,baseline:0.01@calibration,imu0:extrinsic_trans:0.01@calibration";
    let args = [
        "perturb",
        "--input",
        "MH_01_easy",
        "--out",
        "out",
        "--perturb",
        spec,
    ];
    ws.rslam(&args).success();
    let (input, out) = (ws.path("MH_01_easy/mav0"), ws.path("out/mav0"));

    // cam0 is not addressed: its pixels are the recorded ones; cam1's are corrupted.
    for (c, cam) in ["cam0", "cam1"].into_iter().enumerate() {
        for (j, t) in STAMPS.iter().enumerate() {
            let after = image::open(out.join(cam).join(format!("data/{t}.png")))
                .unwrap()
                .into_luma8()
                .into_raw();
            assert_eq!(after == frame(c, j).into_raw(), c == 0, "{cam} frame {j}");
        }
    }
    assert_same_files(
        &input,
        &out,
        &[
            "cam0/sensor.yaml",
            "imu0/data.csv",
            "state_groundtruth_estimate0/data.csv",
        ],
    );

    let recorded = rslam_core::dataset::euroc::read_euroc(&ws.path("MH_01_easy")).unwrap();
    let written = rslam_core::dataset::euroc::read_euroc(&ws.path("out")).unwrap();
    let manifest = rslam_core::dataset::Manifest::read(&ws.path("out")).unwrap();
    let record = &manifest.extra["calibration"];
    let delta = record["baseline_offset_m"].as_f64().unwrap();
    assert!(delta != 0.0);
    // cam1: the same camera, moved by δ along cam0's x axis.
    let (cam0, cam1) = (&written.cameras[0].camera, &written.cameras[1].camera);
    let recorded_cam1 = &recorded.cameras[1].camera;
    assert_eq!(cam1.intrinsics, recorded_cam1.intrinsics);
    assert_eq!(cam1.distortion, recorded_cam1.distortion);
    let shift = cam0
        .body_from_camera
        .inverse()
        .compose(&cam1.body_from_camera)
        .translation
        - cam0
            .body_from_camera
            .inverse()
            .compose(&recorded_cam1.body_from_camera)
            .translation;
    assert!(
        (shift.x - delta).abs() < 1e-9 && shift.y.abs() < 1e-9 && shift.z.abs() < 1e-9,
        "{shift} vs δ {delta}"
    );
    assert!((record["baseline_m"]["written"].as_f64().unwrap() - delta).abs() < 1e-9);
    assert_eq!(
        record["baseline_m"]["true"],
        record["baseline_m"]["nominal"]
    );
    // imu0: moved by the recorded offset, noise parameters kept.
    let (imu, recorded_imu) = (
        &written.imu.as_ref().unwrap().imu,
        &recorded.imu.as_ref().unwrap().imu,
    );
    assert_eq!(
        imu.gyroscope_noise_density,
        recorded_imu.gyroscope_noise_density
    );
    assert_eq!(
        imu.accelerometer_random_walk,
        recorded_imu.accelerometer_random_walk
    );
    let imu_record = record["sensors"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "imu0")
        .unwrap();
    let written_t_bs: Vec<f64> = imu_record["written_T_BS"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let moved = imu.body_from_imu.translation;
    assert!(moved.length() > 0.0 && moved.length() < 0.06, "{moved}");
    for (axis, row) in [3, 7, 11].into_iter().enumerate() {
        assert!((written_t_bs[row] - moved[axis]).abs() < 1e-9);
    }
    // ORB-SLAM3's stereo settings state the written baseline.
    let settings = std::fs::read_to_string(ws.path("out/orbslam3_stereo.yaml")).unwrap();
    let t_c1_c2 = settings.split("Stereo.T_c1_c2").nth(1).unwrap();
    let data = t_c1_c2
        .split("data: [")
        .nth(1)
        .unwrap()
        .split(']')
        .next()
        .unwrap();
    let x: f64 = data.split(',').nth(3).unwrap().trim().parse().unwrap();
    assert!(
        (x - delta).abs() < 1e-6,
        "Stereo.T_c1_c2 x {x} vs δ {delta}"
    );

    let verify = ws.rslam(&["verify", "out"]);
    assert!(verify.success().contains("out: ok"), "{}", verify.stdout());
}
