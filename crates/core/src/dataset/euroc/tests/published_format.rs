//! The written files checked against the published EuRoC format by a parser of their own
//! (plain string splitting, none of the crate's readers), and a hand-written sequence in the
//! published style read by [`read_euroc`].

use std::path::Path;

use glam::DQuat;

use super::fixture;
use crate::dataset::euroc::read_euroc;

fn lines(path: &Path) -> Vec<String> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(str::to_string)
        .collect()
}

/// The numbers of `key: [..]` in a sensor.yaml, the list possibly spanning lines.
fn yaml_list(text: &str, key: &str) -> Vec<f64> {
    let start = text
        .find(&format!("{key}: ["))
        .unwrap_or_else(|| panic!("{key} in\n{text}"));
    let rest = &text[start + key.len() + 3..];
    let inside = &rest[..rest.find(']').unwrap()];
    inside
        .split(',')
        .map(|v| v.trim().parse::<f64>().unwrap())
        .collect()
}

fn yaml_scalar<'t>(text: &'t str, key: &str) -> &'t str {
    text.lines()
        .find_map(|l| l.strip_prefix(&format!("{key}: ")))
        .unwrap_or_else(|| panic!("{key} in\n{text}"))
        .split(" #")
        .next()
        .unwrap()
        .trim()
}

#[test]
fn written_files_follow_the_published_format() {
    let dir = tempfile::tempdir().unwrap();
    let times = fixture::write(dir.path());
    let mav = dir.path().join("mav0");

    for name in ["cam0", "cam1"] {
        let csv = lines(&mav.join(name).join("data.csv"));
        assert_eq!(csv[0], "#timestamp [ns],filename");
        assert_eq!(csv.len(), 1 + times.len());
        for (line, t) in csv[1..].iter().zip(&times) {
            let (stamp, file) = line.split_once(',').unwrap();
            assert!(
                stamp.bytes().all(|b| b.is_ascii_digit()),
                "integer ns: {line}"
            );
            assert_eq!(stamp.parse::<u64>().unwrap(), *t);
            assert_eq!(file, format!("{stamp}.png"));
            assert!(mav.join(name).join("data").join(file).is_file());
        }
        let yaml = std::fs::read_to_string(mav.join(name).join("sensor.yaml")).unwrap();
        assert_eq!(
            yaml.lines().next(),
            Some("# General sensor definitions."),
            "as MH_01_easy"
        );
        assert_eq!(yaml_scalar(&yaml, "sensor_type"), "camera");
        assert_eq!(yaml_scalar(&yaml, "camera_model"), "pinhole");
        assert_eq!(yaml_scalar(&yaml, "distortion_model"), "radial-tangential");
        assert_eq!(yaml_scalar(&yaml, "rate_hz"), "20");
        assert_eq!(yaml_list(&yaml, "resolution"), [6.0, 4.0]);
        assert!(
            yaml.contains("T_BS:\n  cols: 4\n  rows: 4\n  data: ["),
            "{yaml}"
        );
        assert_eq!(yaml_list(&yaml, "intrinsics"), [458.654, 457.296, 2.5, 1.5]);
        assert_eq!(yaml_list(&yaml, "distortion_coefficients").len(), 4);
    }
    // T_BS: 16 numbers, row-major: translation in the last column, 0 0 0 1 last.
    let cam0 = std::fs::read_to_string(mav.join("cam0/sensor.yaml")).unwrap();
    let t_bs = yaml_list(&cam0, "data");
    assert_eq!(t_bs.len(), 16);
    let camera = &fixture::cameras()[0];
    let r = glam::DMat3::from_quat(camera.body_from_camera.rotation);
    for (i, v) in t_bs[..12].iter().enumerate() {
        let (row, col) = (i / 4, i % 4);
        let want = if col == 3 {
            camera.body_from_camera.translation[row]
        } else {
            r.col(col)[row]
        };
        assert!(
            (v - want).abs() < 1e-12,
            "T_BS[{row}][{col}] = {v}, expected {want}"
        );
    }
    assert_eq!(&t_bs[12..], [0.0, 0.0, 0.0, 1.0]);

    let imu = lines(&mav.join("imu0/data.csv"));
    assert_eq!(
        imu[0],
        "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]"
    );
    let first: Vec<&str> = imu[1].split(',').collect();
    assert_eq!(first.len(), 7);
    assert_eq!(first[0], fixture::START_NS.to_string());
    assert_eq!(
        first[4].parse::<f64>().unwrap(),
        8.147_691_708_333_333,
        "a_x in column 5"
    );
    let imu_yaml = std::fs::read_to_string(mav.join("imu0/sensor.yaml")).unwrap();
    assert_eq!(
        imu_yaml.lines().next(),
        Some("#Default imu sensor yaml file"),
        "as MH_01_easy"
    );
    assert_eq!(yaml_scalar(&imu_yaml, "sensor_type"), "imu");
    assert_eq!(yaml_scalar(&imu_yaml, "rate_hz"), "200");
    assert_eq!(
        yaml_list(&imu_yaml, "data"),
        glam::DMat4::IDENTITY.to_cols_array()
    );
    for (key, value) in [
        ("gyroscope_noise_density", 1.6968e-4),
        ("gyroscope_random_walk", 1.9393e-5),
        ("accelerometer_noise_density", 2.0e-3),
        ("accelerometer_random_walk", 3.0e-3),
    ] {
        assert_eq!(
            yaml_scalar(&imu_yaml, key).parse::<f64>().unwrap(),
            value,
            "{key}"
        );
    }

    let gt = lines(&mav.join("state_groundtruth_estimate0/data.csv"));
    assert_eq!(
        gt[0],
        "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad s^-1], b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]"
    );
    let row: Vec<f64> = gt[1].split(',').map(|v| v.parse().unwrap()).collect();
    assert_eq!(row.len(), 17);
    assert!(gt[1]
        .split(',')
        .next()
        .unwrap()
        .bytes()
        .all(|b| b.is_ascii_digit()));
    // Row 0 holds tilted(): w first, then x y z.
    let q: DQuat = fixture::tilted();
    assert!(q.w.abs() < 0.9 && q.x.abs() > 0.05 && q.y.abs() > 0.05 && q.z.abs() > 0.05);
    let written = [row[4], row[5], row[6], row[7]];
    for (got, want) in written.iter().zip([q.w, q.x, q.y, q.z]) {
        assert!(
            (got - want).abs() < 1e-12,
            "q columns {written:?}, expected w x y z {q:?}"
        );
    }
    assert_eq!(&row[1..4], [4.688319, -1.786938, 0.783338]);
    assert_eq!(
        &row[14..],
        [-0.025266, 0.136696, 0.075593],
        "accelerometer bias last"
    );
}

/// cam0/sensor.yaml of MH_01_easy as published.
const MH01_CAM0_YAML: &str = "# General sensor definitions.
sensor_type: camera
comment: VI-Sensor cam0 (MT9M034)

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
resolution: [752, 480]
camera_model: pinhole
intrinsics: [458.654, 457.296, 367.215, 248.375] #fu, fv, cu, cv
distortion_model: radial-tangential
distortion_coefficients: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]
";

/// imu0/sensor.yaml of MH_01_easy as published.
const MH01_IMU_YAML: &str = "#Default imu sensor yaml file
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

const MH01_CAM_CSV: &str = "#timestamp [ns],filename\r
1403636579763555584,1403636579763555584.png\r
1403636579813555456,1403636579813555456.png\r
";

const MH01_IMU_CSV: &str = "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]
1403636579758555392,-0.099134701513277898,0.14730578886832138,0.02722713633111154,8.1476917083333333,-0.37592158333333331,-2.4026292499999999
1403636579763555584,-0.099134701513277898,0.14032447186034408,0.029321531433504733,8.033280791666666,-0.40861041666666664,-2.4026292499999999
";

const MH01_GT_CSV: &str = "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad s^-1], b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]
1403636580838555648,4.688319,-1.786938,0.783338,0.534108,-0.153029,-0.827383,-0.082152,-0.027876,0.033207,0.800006,-0.003172,0.021267,0.078502,-0.025266,0.136696,0.075593
1403636580843555328,4.688177,-1.786770,0.787350,0.534640,-0.152990,-0.826976,-0.082863,-0.029272,0.033992,0.804621,-0.003172,0.021267,0.078502,-0.025266,0.136696,0.075593
";

/// Lays out a MH_01_easy-style sequence (two frames per camera, two IMU and two ground-truth
/// lines, no rslam manifest) under `root`.
pub fn write_published_style(root: &Path) {
    let mav = root.join("mav0");
    for cam in ["cam0", "cam1"] {
        let data = mav.join(cam).join("data");
        std::fs::create_dir_all(&data).unwrap();
        std::fs::write(mav.join(cam).join("sensor.yaml"), MH01_CAM0_YAML).unwrap();
        std::fs::write(mav.join(cam).join("data.csv"), MH01_CAM_CSV).unwrap();
        for t in ["1403636579763555584", "1403636579813555456"] {
            image::GrayImage::new(752, 480)
                .save(data.join(format!("{t}.png")))
                .unwrap();
        }
    }
    std::fs::create_dir_all(mav.join("imu0")).unwrap();
    std::fs::write(mav.join("imu0/sensor.yaml"), MH01_IMU_YAML).unwrap();
    std::fs::write(mav.join("imu0/data.csv"), MH01_IMU_CSV).unwrap();
    std::fs::create_dir_all(mav.join("state_groundtruth_estimate0")).unwrap();
    std::fs::write(
        mav.join("state_groundtruth_estimate0/data.csv"),
        MH01_GT_CSV,
    )
    .unwrap();
    // Folders rslam does not read.
    std::fs::create_dir_all(mav.join("leica0")).unwrap();
    std::fs::write(
        mav.join("body.yaml"),
        "comment: The body frame is the IMU frame\n",
    )
    .unwrap();
}

#[test]
fn a_published_style_sequence_reads() {
    let dir = tempfile::tempdir().unwrap();
    write_published_style(dir.path());
    let read = read_euroc(dir.path()).unwrap();
    assert_eq!(read.cameras.len(), 2);
    let cam0 = &read.cameras[0];
    assert_eq!(cam0.camera.name, "cam0");
    assert_eq!(cam0.camera.comment, "VI-Sensor cam0 (MT9M034)");
    assert_eq!(cam0.camera.rate_hz, 20.0);
    let k = cam0.camera.intrinsics;
    assert_eq!(
        (k.width, k.height, k.fx, k.fy, k.cx, k.cy),
        (752, 480, 458.654, 457.296, 367.215, 248.375)
    );
    assert_eq!(cam0.camera.distortion.p2, 1.76187114e-05);
    let m = cam0.camera.body_from_camera.to_row_major();
    // Re-orthonormalised through a quaternion; the published matrix is orthonormal to ~1e-9.
    assert!((m[1] - -0.999880929698).abs() < 1e-6 && (m[3] - -0.0216401454975).abs() < 1e-12);
    assert_eq!(
        cam0.frames.iter().map(|f| f.t_ns).collect::<Vec<_>>(),
        [1403636579763555584, 1403636579813555456]
    );
    assert_eq!(
        cam0.camera.colour,
        crate::dataset::euroc::CameraColour::Grey
    );

    let imu = read.imu.unwrap();
    assert_eq!(imu.imu.rate_hz, 200.0);
    assert_eq!(imu.imu.gyroscope_noise_density, 1.6968e-4);
    assert_eq!(imu.imu.accelerometer_random_walk, 3.0e-3);
    assert_eq!(imu.samples.len(), 2);
    assert_eq!(imu.samples[1].t_ns, 1403636579763555584);
    assert_eq!(imu.samples[0].accel.x, 8.147_691_708_333_333);

    let truth = read.ground_truth.unwrap();
    assert_eq!(truth.len(), 2);
    assert_eq!(truth[0].t_ns, 1403636580838555648);
    let q = truth[0].world_from_body.rotation;
    let norm =
        (0.534108f64.powi(2) + 0.153029f64.powi(2) + 0.827383f64.powi(2) + 0.082152f64.powi(2))
            .sqrt();
    assert!((q.w - 0.534108 / norm).abs() < 1e-12, "w first: {q:?}");
    assert!((q.z - -0.082152 / norm).abs() < 1e-12, "{q:?}");
    assert_eq!(truth[1].velocity.z, 0.804621);
    assert_eq!(truth[0].accel_bias.y, 0.136696);

    // The rslam eval reader takes the same file, in seconds.
    let eval = crate::trajectory_io::read_trajectory(
        &dir.path().join("mav0/state_groundtruth_estimate0/data.csv"),
        None,
    )
    .unwrap();
    assert_eq!(eval.trajectory.poses[0], truth[0].world_from_body);
}
