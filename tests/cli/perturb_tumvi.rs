//! `rslam perturb --input <TUM-VI export>`: TUM-VI's EuRoC-style export (`dataset-room1_512_16/`:
//! `mav0/` without sensor.yaml files, 16-bit grey frames, `mocap0/` ground truth, Kalibr and DSO
//! calibration in `dso/`) copied with its IMU or written calibration perturbed, its own files
//! kept; image corruptions on 16-bit frames made from their high byte; `rslam eval` on its mocap0
//! ground truth.

use std::path::Path;

use rslam_core::dataset::euroc::{read_camchain, read_euroc, CameraColour};
use rslam_core::dataset::Manifest;

use crate::dataset_check::{assert_same_files, tree};
use crate::harness::Workspace;

/// Three cam0/cam1 stamps 50 ms apart (20 Hz; TUM-VI's stamps are any nanosecond, cam0's and
/// cam1's equal).
const STAMPS: [u64; 3] = [
    1_520_530_308_199_447_626,
    1_520_530_308_249_448_626,
    1_520_530_308_299_447_926,
];
const SIDE: u32 = 64;

/// TUM-VI's dso/camchain.yaml as Kalibr writes it: cam0's and cam1's `T_cam_imu`, lens and
/// intrinsics are the published 512×512 calibration (as OpenVINS ships it,
/// config/tum_vi/kalibr_imucam_chain.yaml), scaled here to 64×64 px (intrinsics ÷ 8);
/// `T_cn_cnm1` is cam1's `T_cam_imu` times cam0's inverse.
const CAMCHAIN: &str = "cam0:
  T_cam_imu:
  - [-0.9995250378696743, 0.029615343885863205, -0.008522328211654736, 0.04727988224914392]
  - [0.0075019185074052044, -0.03439736061393144, -0.9993800792498829, -0.047443232143367084]
  - [-0.02989013031643309, -0.998969345370175, 0.03415885127385616, -0.0681999605066297]
  - [0.0, 0.0, 0.0, 1.0]
  cam_overlaps: [1]
  camera_model: pinhole
  distortion_coeffs: [0.0034823894022493434, 0.0007150348452162257, -0.0020532361418706202, 0.00020293673591811182]
  distortion_model: equidistant
  intrinsics: [23.872309643910896, 23.871663381515325, 31.866463257419344, 32.1121803624563]
  resolution: [64, 64]
  rostopic: /cam0/image_raw
cam1:
  T_cam_imu:
  - [-0.9995110484978581, 0.030299116376600627, -0.0077218830287333565, -0.053697434688869734]
  - [0.008104079263822521, 0.012511643720192351, -0.9998888851620987, -0.046131737923635924]
  - [-0.030199136245891378, -0.9994625667418545, -0.012751072573940885, -0.07149261284195751]
  - [0.0, 0.0, 0.0, 1.0]
  T_cn_cnm1:
  - [0.9999994457734942, -0.0008233639921576, -0.0006561436136444, -0.1010611027518054]
  - [0.0007916877528168, 0.9988994619156748, -0.0468960362405898, -0.0019764575873431]
  - [0.0006940340102243, 0.0468954907887005, 0.9988995601463044, -0.0011756424802046]
  - [0.0, 0.0, 0.0, 1.0]
  cam_overlaps: [0]
  camera_model: pinhole
  distortion_coeffs: [0.0034003170790442797, 0.001766278153469831, -0.00266312569781606, 0.0003299517423931039]
  distortion_model: equidistant
  intrinsics: [23.80529621176853, 23.80430480902445, 31.574937146044978, 31.864653830795228]
  resolution: [64, 64]
  rostopic: /cam1/image_raw
";

/// TUM-VI's dso/imu_config.yaml: the BMI160's noise as the TUM-VI page gives it (inflated for
/// estimators; the same values as OpenVINS's config/tum_vi/kalibr_imu_chain.yaml).
const IMU_CONFIG: &str = "accelerometer_noise_density: 0.0028     #Noise density (continuous-time)
accelerometer_random_walk:   0.00086    #Bias random walk
gyroscope_noise_density:     0.00016    #Noise density (continuous-time)
gyroscope_random_walk:       0.000022   #Bias random walk
rostopic:                    /imu0      #the IMU ROS topic
update_rate:                 200.0      #Hz (for discretization of the values above)
";

const MOCAP_HEADER: &str = "#timestamp [ns], p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z []";

/// A textured frame with values over the whole 16-bit range, low bytes included.
fn frame16(camera: usize, j: usize) -> image::ImageBuffer<image::Luma<u16>, Vec<u16>> {
    image::ImageBuffer::from_fn(SIDE, SIDE, |x, y| {
        let v = (x * 977 + y * 431 + j as u32 * 1013 + camera as u32 * 59) % 40_000 + 9_000;
        image::Luma([v as u16])
    })
}

fn high_byte(
    frame: &image::ImageBuffer<image::Luma<u16>, Vec<u16>>,
) -> image::ImageBuffer<image::Luma<u8>, Vec<u8>> {
    image::ImageBuffer::from_fn(frame.width(), frame.height(), |x, y| {
        image::Luma([(frame.get_pixel(x, y)[0] >> 8) as u8])
    })
}

/// 120 Hz motion-capture poses of the IMU along an arc, TUM-VI's mocap0/data.csv.
fn mocap_csv() -> String {
    let mut text = format!("{MOCAP_HEADER}\n");
    let t0 = STAMPS[0] - 20_000_000;
    for i in 0..16u64 {
        let s = i as f64 / 120.0;
        let half = 0.3 * s;
        text += &format!(
            "{},{:.9},{:.9},{:.9},{:.9},0.0,0.0,{:.9}\n",
            t0 + i * 8_333_333,
            0.8 + 0.4 * (8.0 * s).sin(),
            -1.2 + 0.4 * (8.0 * s).cos(),
            1.4 + 0.05 * s,
            half.cos(),
            half.sin()
        );
    }
    text
}

/// 200 Hz BMI160 readings (gravity mostly along x, as TUM-VI's IMU hangs) around the frames.
fn imu_csv() -> String {
    let mut text = String::from("#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n");
    let t0 = STAMPS[0] - 10_000_000;
    for i in 0..24u64 {
        let s = i as f64 * 0.005;
        text += &format!(
            "{},{:.7},{:.7},{:.7},{:.7},{:.7},{:.7}\n",
            t0 + i * 5_000_000,
            -0.0977 + 0.01 * s,
            0.0454,
            0.0209 - 0.02 * s,
            9.389 + 0.1 * s,
            0.359,
            -1.7458
        );
    }
    text
}

/// Lays out a TUM-VI-style export under `root`: 16-bit frames, or with `eight_bit` their high
/// bytes as 8-bit frames.
pub(crate) fn write_tum_vi_style(root: &Path, eight_bit: bool) {
    let mav = root.join("mav0");
    for (c, cam) in ["cam0", "cam1"].into_iter().enumerate() {
        let data = mav.join(cam).join("data");
        std::fs::create_dir_all(&data).unwrap();
        let mut csv = String::from("#timestamp [ns],filename\n");
        for (j, t) in STAMPS.iter().enumerate() {
            csv += &format!("{t},{t}.png\n");
            let path = data.join(format!("{t}.png"));
            if eight_bit {
                high_byte(&frame16(c, j)).save(path).unwrap();
            } else {
                frame16(c, j).save(path).unwrap();
            }
        }
        std::fs::write(mav.join(cam).join("data.csv"), csv).unwrap();
    }
    std::fs::create_dir_all(mav.join("imu0")).unwrap();
    std::fs::write(mav.join("imu0/data.csv"), imu_csv()).unwrap();
    std::fs::create_dir_all(mav.join("mocap0")).unwrap();
    std::fs::write(mav.join("mocap0/data.csv"), mocap_csv()).unwrap();
    let dso = root.join("dso");
    for cam in ["cam0", "cam1"] {
        std::fs::create_dir_all(dso.join(cam)).unwrap();
        std::fs::write(
            dso.join(cam).join("camera.txt"),
            "EquiDistant 0.373004838186 0.372994740336 0.498890050897 0.502739307398 0.00348238940225 0.000715034845216 -0.00205323614187 0.000202936735918\n64 64\ncrop\n64 64\n",
        )
        .unwrap();
        let response: Vec<String> = (0..256).map(|i| format!("{}", i * 257)).collect();
        std::fs::write(dso.join(cam).join("pcalib.txt"), response.join(" ") + "\n").unwrap();
        image::ImageBuffer::<image::Luma<u16>, _>::from_fn(SIDE, SIDE, |x, y| {
            image::Luma([65_535 - ((x as i32 - 32).pow(2) + (y as i32 - 32).pow(2)) as u16 * 8])
        })
        .save(dso.join(cam).join("vignette.png"))
        .unwrap();
    }
    std::fs::write(dso.join("camchain.yaml"), CAMCHAIN).unwrap();
    std::fs::write(dso.join("imu_config.yaml"), IMU_CONFIG).unwrap();
    std::fs::write(dso.join("gt_imu.csv"), mocap_csv()).unwrap();
    let imu_txt: String = imu_csv()
        .lines()
        .skip(1)
        .map(|l| l.replace(',', " ") + "\n")
        .collect();
    std::fs::write(dso.join("imu.txt"), imu_txt).unwrap();
}

/// The lines of `stderr` that report an error (the adapter line comes before).
fn error_lines(stderr: &str) -> usize {
    stderr.lines().filter(|l| l.starts_with("error")).count()
}

/// Relative paths (with `/`) of every file under `dir`.
fn files_under(dir: &Path) -> Vec<String> {
    tree(dir).into_keys().collect()
}

/// Every dso/ file of the fixture.
const DSO_FILES: [&str; 10] = [
    "cam0/camera.txt",
    "cam0/pcalib.txt",
    "cam0/vignette.png",
    "cam1/camera.txt",
    "cam1/pcalib.txt",
    "cam1/vignette.png",
    "camchain.yaml",
    "gt_imu.csv",
    "imu.txt",
    "imu_config.yaml",
];

fn perturb(ws: &Workspace, spec: &str) -> Manifest {
    let args = [
        "perturb",
        "--input",
        "dataset-room1_512_16",
        "--out",
        "out",
        "--perturb",
        spec,
    ];
    let run = ws.rslam(&args);
    run.success();
    assert!(
        run.stderr()
            .contains("wrote 3 frames from cam0, 3 frames from cam1, 24 IMU samples to out"),
        "{}",
        run.stderr()
    );
    let verify = ws.rslam(&["verify", "out"]);
    assert!(verify.success().contains("out: ok"), "{}", verify.stdout());
    let manifest = Manifest::read(&ws.path("out")).unwrap();
    assert_eq!(manifest.extra["layout"], "tum-vi");
    manifest
}

#[test]
fn perturb_tumvi_imu_items_keep_the_16_bit_frames_mocap0_and_dso_files() {
    let ws = Workspace::new();
    write_tum_vi_style(&ws.path("dataset-room1_512_16"), false);
    let manifest = perturb(&ws, "imu_noise:3");
    let (input, out) = (ws.path("dataset-room1_512_16"), ws.path("out"));

    let mav_files = files_under(&out.join("mav0"));
    let mut expected = vec!["imu0/data.csv".to_string(), "mocap0/data.csv".to_string()];
    for cam in ["cam0", "cam1"] {
        expected.push(format!("{cam}/data.csv"));
        expected.extend(STAMPS.iter().map(|t| format!("{cam}/data/{t}.png")));
    }
    expected.sort();
    assert_eq!(
        mav_files, expected,
        "no sensor.yaml, nothing but the input's files"
    );
    let mut frames: Vec<String> = expected
        .iter()
        .filter(|f| f.ends_with(".png"))
        .map(|f| format!("mav0/{f}"))
        .collect();
    frames.extend(
        [
            "mav0/cam0/data.csv",
            "mav0/cam1/data.csv",
            "mav0/mocap0/data.csv",
        ]
        .map(String::from),
    );
    let frames: Vec<&str> = frames.iter().map(String::as_str).collect();
    assert_same_files(&input, &out, &frames);
    let first = image::open(out.join(format!("mav0/cam1/data/{}.png", STAMPS[0]))).unwrap();
    assert_eq!(first.color(), image::ColorType::L16, "still 16-bit");

    // imu0 carries the added noise; dso/imu.txt, which repeats its readings, is left out.
    assert_ne!(
        std::fs::read(out.join("mav0/imu0/data.csv")).unwrap(),
        std::fs::read(input.join("mav0/imu0/data.csv")).unwrap()
    );
    let dso: Vec<&str> = DSO_FILES
        .iter()
        .copied()
        .filter(|f| *f != "imu.txt")
        .collect();
    assert_same_files(&input.join("dso"), &out.join("dso"), &dso);
    assert!(!out.join("dso/imu.txt").exists());
    assert!(!out.join("orbslam3_stereo.yaml").exists());
    let record = &manifest.extra["tum_vi"];
    assert_eq!(record["camchain"], "copied");
    assert_eq!(record["left_out"][0]["file"], "dso/imu.txt");
    assert!(manifest.extra["imu_biases_in_ground_truth"]
        .as_str()
        .unwrap()
        .starts_with("not written"));
    // The noise added is the density imu_config.yaml gives, scaled: sqrt(3² − 1) of 0.00016.
    let added = manifest.extra["imu_perturbation"]["noise_added"]["gyroscope_noise_density"]
        .as_f64()
        .unwrap();
    assert!((added - 0.00016 * 8f64.sqrt()).abs() < 1e-12, "{added}");

    // The copy reads back as a TUM-VI export.
    let back = read_euroc(&out).unwrap();
    assert!(back.tum_vi.is_some());
    assert_eq!(back.cameras[1].camera.colour, CameraColour::Grey16);
    // Rates: the cameras' from their stamps' median interval (50.001 ms), imu0's update_rate.
    let rate = back.cameras[0].camera.rate_hz;
    assert!((rate - 1e9 / 50_001_000.0).abs() < 1e-9, "{rate}");
    let imu = back.imu.unwrap();
    assert_eq!((imu.imu.rate_hz, imu.samples.len()), (200.0, 24));
}

#[test]
fn perturb_tumvi_baseline_at_calibration_rewrites_cam1_in_camchain_only() {
    let ws = Workspace::new();
    write_tum_vi_style(&ws.path("dataset-room1_512_16"), false);
    let manifest = perturb(&ws, "baseline:0.01@calibration");
    let (input, out) = (ws.path("dataset-room1_512_16"), ws.path("out"));
    let delta = manifest.extra["calibration"]["baseline_offset_m"]
        .as_f64()
        .unwrap();
    assert!(delta != 0.0);

    let before = std::fs::read_to_string(input.join("dso/camchain.yaml")).unwrap();
    let after = std::fs::read_to_string(out.join("dso/camchain.yaml")).unwrap();
    let changed: Vec<usize> = before
        .lines()
        .zip(after.lines())
        .enumerate()
        .filter(|(_, (a, b))| a != b)
        .map(|(i, _)| i + 1)
        .collect();
    assert_eq!(before.lines().count(), after.lines().count());
    // cam1's T_cam_imu rows (lines 16–18) and T_cn_cnm1 rows (21–23); the bottom rows stay.
    assert_eq!(changed, [16, 17, 18, 21, 22, 23], "{after}");

    let (recorded, written) = (
        read_camchain(&input.join("dso/camchain.yaml")).unwrap(),
        read_camchain(&out.join("dso/camchain.yaml")).unwrap(),
    );
    let cam0 = recorded.cameras[0].camera_from_imu;
    assert_eq!(written.cameras[0].camera_from_imu, cam0);
    let cam1_before = recorded.cameras[1].camera_from_imu;
    let cam1_after = written.cameras[1].camera_from_imu;
    // cam1's centre in cam0's frame moved by δ along cam0's x axis, nothing else.
    let centre = |cam1: rslam_core::Pose| cam0.compose(&cam1.inverse()).translation;
    let shift = centre(cam1_after) - centre(cam1_before);
    assert!(
        (shift.x - delta).abs() < 1e-12 && shift.y.abs() < 1e-12 && shift.z.abs() < 1e-12,
        "{shift} vs δ {delta}"
    );
    let rotation = cam1_after.rotation.angle_between(cam1_before.rotation);
    assert!(rotation < 1e-12, "{rotation}");
    // T_cn_cnm1 as written says the same as the two T_cam_imu.
    let t_cn_cnm1: Vec<f64> = after
        .lines()
        .skip(20)
        .take(3)
        .flat_map(|l| {
            let inside = l
                .split('[')
                .nth(1)
                .unwrap()
                .trim_end_matches(']')
                .to_string();
            inside
                .split(',')
                .map(|v| v.trim().parse::<f64>().unwrap())
                .collect::<Vec<_>>()
        })
        .collect();
    let expected = cam1_after.compose(&cam0.inverse());
    for (axis, index) in [3, 7, 11].into_iter().enumerate() {
        assert!((t_cn_cnm1[index] - expected.translation[axis]).abs() < 1e-12);
    }

    let dso: Vec<&str> = DSO_FILES
        .iter()
        .copied()
        .filter(|f| *f != "camchain.yaml")
        .collect();
    assert_same_files(&input.join("dso"), &out.join("dso"), &dso);
    assert_same_files(
        &input.join("mav0"),
        &out.join("mav0"),
        &["imu0/data.csv", "mocap0/data.csv"],
    );
    assert_eq!(manifest.extra["tum_vi"]["camchain"], "rewritten");
    assert_eq!(manifest.extra["tum_vi"]["camchain_moved"][0], "cam1");
}

#[test]
fn perturb_tumvi_corrupts_16_bit_frames_as_their_high_byte_and_writes_257_times_the_result() {
    let spec = "gaussian_noise:3,cam1:fog:2";
    let ws = Workspace::new();
    write_tum_vi_style(&ws.path("dataset-room1_512_16"), false);
    let manifest = perturb(&ws, spec);
    let ws8 = Workspace::new();
    write_tum_vi_style(&ws8.path("dataset-room1_512_16"), true);
    perturb(&ws8, spec);
    let (input, out, out8) = (
        ws.path("dataset-room1_512_16"),
        ws.path("out"),
        ws8.path("out"),
    );
    for (c, cam) in ["cam0", "cam1"].into_iter().enumerate() {
        assert!(
            manifest.extra["cameras"][c]["written_frames"]
                .as_str()
                .unwrap()
                .contains("high byte"),
            "{}",
            manifest.extra["cameras"][c]
        );
        for (j, t) in STAMPS.iter().enumerate() {
            let name = format!("mav0/{cam}/data/{t}.png");
            let wide = image::open(out.join(&name)).unwrap();
            assert_eq!(wide.color(), image::ColorType::L16, "{name}");
            let narrow = image::open(out8.join(&name)).unwrap().into_luma8();
            assert_ne!(narrow, high_byte(&frame16(c, j)), "{name} corrupted");
            let expected: Vec<u16> = narrow.iter().map(|&v| v as u16 * 257).collect();
            assert!(wide.into_luma16().into_raw() == expected, "{name}");
        }
    }
    assert_same_files(&input.join("dso"), &out.join("dso"), &DSO_FILES);
    assert_same_files(
        &input.join("mav0"),
        &out.join("mav0"),
        &["imu0/data.csv", "mocap0/data.csv", "cam0/data.csv"],
    );

    // A frame of another bit depth than the camera's first is refused when it is read.
    for (first_eight_bit, odd_frame, expected) in [
        (true, 2, "16-bit samples, but the GPU frames are 8-bit"),
        (false, 1, "expected a 16-bit grey PNG"),
    ] {
        let ws = Workspace::new();
        write_tum_vi_style(&ws.path("mixed"), first_eight_bit);
        let odd = format!("mixed/mav0/cam0/data/{}.png", STAMPS[odd_frame]);
        if first_eight_bit {
            frame16(0, odd_frame).save(ws.path(&odd)).unwrap();
        } else {
            high_byte(&frame16(0, odd_frame))
                .save(ws.path(&odd))
                .unwrap();
        }
        let err = ws
            .rslam(&[
                "perturb",
                "--input",
                "mixed",
                "--out",
                "y",
                "--perturb",
                "gaussian_noise:3",
            ])
            .fails_with(2, &[&odd, expected]);
        assert_eq!(error_lines(&err), 1, "{err}");
        assert!(!ws.path("y/rslam.json").exists());
    }
}

#[test]
fn perturb_tumvi_missing_or_malformed_calibration_is_a_one_line_error_naming_the_file() {
    let ws = Workspace::new();
    write_tum_vi_style(&ws.path("seq"), false);
    let run = |ws: &Workspace, fragments: &[&str]| {
        let err = ws
            .rslam(&[
                "perturb",
                "--input",
                "seq",
                "--out",
                "x",
                "--perturb",
                "imu_noise:2",
            ])
            .fails_with(2, fragments);
        assert_eq!(error_lines(&err), 1, "{err}");
        assert!(!ws.path("x").exists());
    };
    let camchain = ws.path("seq/dso/camchain.yaml");
    for (text, fragments) in [
        (
            CAMCHAIN.replacen("  - [0.0, 0.0, 0.0, 1.0]\n", "", 1),
            &["camchain.yaml:2:", "'T_cam_imu': 3 rows; expected 4 rows"][..],
        ),
        (
            CAMCHAIN.replacen("0.04727988224914392", "0.0472x", 1),
            &["camchain.yaml:3:", "0.0472x"][..],
        ),
        (
            CAMCHAIN.replacen("-0.9995250378696743", "-0.5", 1),
            &["camchain.yaml:2:", "rotation"][..],
        ),
        (
            CAMCHAIN.replace("cam1:", "imu0:"),
            &["camchain.yaml:14:", "expected a camera block 'cam0:'"][..],
        ),
        (
            CAMCHAIN.split("cam1:").next().unwrap().to_string(),
            &["camchain.yaml", "no 'cam1:' block for mav0/cam1/"][..],
        ),
    ] {
        std::fs::write(&camchain, text).unwrap();
        run(&ws, fragments);
    }
    std::fs::remove_file(&camchain).unwrap();
    run(
        &ws,
        &[
            "cam0/sensor.yaml",
            "no such file, and no",
            "dso/camchain.yaml",
        ],
    );
    std::fs::write(&camchain, CAMCHAIN).unwrap();
    std::fs::write(ws.path("seq/dso/imu_config.yaml"), "update_rate: 200.0\n").unwrap();
    run(
        &ws,
        &["imu_config.yaml", "missing key 'gyroscope_noise_density'"],
    );
}

#[test]
fn perturb_tumvi_eval_reads_the_mocap0_ground_truth() {
    let ws = Workspace::new();
    write_tum_vi_style(&ws.path("datasets/room1"), false);
    // An estimate that is the ground truth moved rigidly: ATE 0 after alignment.
    let mut estimate = String::new();
    for line in mocap_csv().lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|f| f.parse().unwrap()).collect();
        estimate += &format!(
            "{:.9} {} {} {} {} {} {} {}\n",
            v[0] / 1e9,
            v[1] + 3.0,
            v[2] - 1.0,
            v[3] + 0.5,
            v[5],
            v[6],
            v[7],
            v[4]
        );
    }
    ws.write("est.txt", &estimate);
    let out = ws
        .rslam(&["eval", "est.txt", "datasets/room1/mav0/mocap0/data.csv"])
        .success();
    assert!(out.contains("pairs\t16 of max. 16"), "{out}");
    assert!(out.contains("      rmse\t0.000000"), "{out}");
    ws.write("runs/method/room1.txt", &estimate);
    let out = ws
        .rslam(&[
            "eval",
            "--runs",
            "runs",
            "--datasets",
            "datasets",
            "--out",
            "report",
        ])
        .success();
    assert!(out.contains("(0 failed)"), "{out}");
}
