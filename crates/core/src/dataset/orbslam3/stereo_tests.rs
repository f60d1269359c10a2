//! The stereo(-inertial) settings for EuRoC's own MH_01_easy calibration, read back by a small
//! parser of their own (string splitting, not the writer's code) and compared with the values
//! ORB-SLAM3 v1.0 ships in `Examples/Stereo/EuRoC.yaml` and `Examples/Stereo-Inertial/EuRoC.yaml`.

use std::collections::BTreeMap;

use glam::{DQuat, DVec3};

use super::{stereo_inertial_settings, stereo_pair_problem, stereo_settings};
use crate::dataset::euroc::{CameraColour, EurocCamera, EurocImu, RadialTangential};
use crate::{Intrinsics, Pose};

/// Largest difference of a written matrix entry from the reference. The example prints 15
/// decimals of inverse(T_BS cam0) · T_BS cam1; rslam keeps each T_BS as a unit quaternion and a
/// translation, which moves the entries by about 3e-13 on MH_01_easy. (ORB-SLAM3 itself reads
/// them as `dt: f`, 32-bit floats, about 6e-8 apart near 1.)
const MATRIX_TOLERANCE: f64 = 1e-9;

/// mav0/cam0/sensor.yaml of MH_01_easy: T_BS, row-major.
#[rustfmt::skip]
const MH01_CAM0_T_BS: [f64; 16] = [
    0.0148655429818, -0.999880929698, 0.00414029679422, -0.0216401454975,
    0.999557249008, 0.0149672133247, 0.025715529948, -0.064676986768,
    -0.0257744366974, 0.00375618835797, 0.999660727178, 0.00981073058949,
    0.0, 0.0, 0.0, 1.0,
];
/// mav0/cam1/sensor.yaml of MH_01_easy: T_BS, row-major.
#[rustfmt::skip]
const MH01_CAM1_T_BS: [f64; 16] = [
    0.0125552670891, -0.999755099723, 0.0182237714554, -0.0198435579556,
    0.999598781151, 0.0130119051815, 0.0251588363115, 0.0453689425024,
    -0.0253898008918, 0.0179005838253, 0.999517347078, 0.00786212447038,
    0.0, 0.0, 0.0, 1.0,
];
/// `Stereo.T_c1_c2` of ORB-SLAM3 v1.0's Examples/Stereo/EuRoC.yaml (the same in
/// Examples/Stereo-Inertial/EuRoC.yaml).
#[rustfmt::skip]
const ORBSLAM3_EUROC_T_C1_C2: [f64; 16] = [
    0.999997256477797, -0.002317135723275, -0.000343393120620, 0.110074137800478,
    0.002312067192432, 0.999898048507103, -0.014090668452683, -0.000156612054392,
    0.000376008102320, 0.014089835846691, 0.999900662638081, 0.000889382785432,
    0.0, 0.0, 0.0, 1.000000000000000,
];

fn mh01_camera(name: &str, t_bs: &[f64; 16], k: [f64; 4], d: [f64; 4]) -> EurocCamera {
    EurocCamera {
        name: name.into(),
        comment: format!("VI-Sensor {name} (MT9M034)"),
        body_from_camera: Pose::from_row_major(t_bs),
        rate_hz: 20.0,
        intrinsics: Intrinsics {
            width: 752,
            height: 480,
            fx: k[0],
            fy: k[1],
            cx: k[2],
            cy: k[3],
        },
        distortion: RadialTangential::from_array(d),
        colour: CameraColour::Grey,
    }
}

/// EuRoC MH_01_easy's cam0 and cam1 as their sensor.yaml files give them.
fn mh01_cameras() -> (EurocCamera, EurocCamera) {
    (
        mh01_camera(
            "cam0",
            &MH01_CAM0_T_BS,
            [458.654, 457.296, 367.215, 248.375],
            [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05],
        ),
        mh01_camera(
            "cam1",
            &MH01_CAM1_T_BS,
            [457.587, 456.134, 379.999, 255.238],
            [-0.28368365, 0.07451284, -0.00010473, -3.55590700e-05],
        ),
    )
}

/// The settings file as key → value text, and its `!!opencv-matrix` entries as 16 numbers.
struct Parsed {
    keys: Vec<String>,
    scalars: BTreeMap<String, String>,
    matrices: BTreeMap<String, Vec<f64>>,
}

impl Parsed {
    fn real(&self, key: &str) -> f64 {
        let text = &self.scalars[key];
        assert!(
            text.contains('.'),
            "{key}: {text}: OpenCV reads a real only with a decimal point"
        );
        text.parse().unwrap()
    }

    fn int(&self, key: &str) -> i64 {
        self.scalars[key].parse().unwrap()
    }
}

fn parse(text: &str) -> Parsed {
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("%YAML:1.0"), "OpenCV's first line");
    let mut parsed = Parsed {
        keys: Vec::new(),
        scalars: BTreeMap::new(),
        matrices: BTreeMap::new(),
    };
    while let Some(line) = lines.next() {
        let line = line.split('#').next().unwrap().trim_end();
        if line.is_empty() {
            continue;
        }
        assert!(
            !line.starts_with(' '),
            "indented outside a matrix: {line:?}"
        );
        let (key, value) = line.split_once(": ").expect(line);
        parsed.keys.push(key.to_string());
        if value != "!!opencv-matrix" {
            parsed.scalars.insert(key.to_string(), value.to_string());
            continue;
        }
        let mut fields = BTreeMap::new();
        let mut data = String::new();
        for line in lines.by_ref() {
            let (field, value) = line.trim().split_once(':').unwrap_or(("", line.trim()));
            if field == "data" || !data.is_empty() {
                data.push_str(if field == "data" { value } else { line.trim() });
                if data.ends_with(']') {
                    break;
                }
            } else {
                fields.insert(field.to_string(), value.trim().to_string());
            }
        }
        assert_eq!(
            (
                fields["rows"].as_str(),
                fields["cols"].as_str(),
                fields["dt"].as_str()
            ),
            ("4", "4", "f"),
            "{key}"
        );
        let numbers: Vec<f64> = data
            .trim()
            .trim_start_matches('[')
            .trim_end_matches(']')
            .split(',')
            .map(|v| v.trim().parse().unwrap())
            .collect();
        assert_eq!(numbers.len(), 16, "{key}");
        parsed.matrices.insert(key.to_string(), numbers);
    }
    parsed
}

fn assert_matrix_close(got: &[f64], want: &[f64; 16], what: &str) {
    let worst = got
        .iter()
        .zip(want)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(
        worst < MATRIX_TOLERANCE,
        "{what}: {worst:e}\n{got:?}\n{want:?}"
    );
}

/// The keys of ORB-SLAM3 v1.0's Examples/Stereo/EuRoC.yaml, in its order.
#[rustfmt::skip]
const STEREO_KEYS: &[&str] = &[
    "File.version", "Camera.type",
    "Camera1.fx", "Camera1.fy", "Camera1.cx", "Camera1.cy",
    "Camera1.k1", "Camera1.k2", "Camera1.p1", "Camera1.p2",
    "Camera2.fx", "Camera2.fy", "Camera2.cx", "Camera2.cy",
    "Camera2.k1", "Camera2.k2", "Camera2.p1", "Camera2.p2",
    "Camera.width", "Camera.height", "Camera.fps", "Camera.RGB",
    "Stereo.ThDepth", "Stereo.T_c1_c2",
];
/// The keys the stereo-inertial file adds after `Stereo.T_c1_c2`.
#[rustfmt::skip]
const IMU_KEYS: &[&str] = &[
    "IMU.T_b_c1",
    "IMU.NoiseGyro", "IMU.NoiseAcc", "IMU.GyroWalk", "IMU.AccWalk", "IMU.Frequency",
];
/// The keys both files end with, as ORB-SLAM3 v1.0's EuRoC examples.
#[rustfmt::skip]
const TRACKING_KEYS: &[&str] = &[
    "ORBextractor.nFeatures", "ORBextractor.scaleFactor", "ORBextractor.nLevels",
    "ORBextractor.iniThFAST", "ORBextractor.minThFAST",
    "Viewer.KeyFrameSize", "Viewer.KeyFrameLineWidth", "Viewer.GraphLineWidth",
    "Viewer.PointSize", "Viewer.CameraSize", "Viewer.CameraLineWidth",
    "Viewer.ViewpointX", "Viewer.ViewpointY", "Viewer.ViewpointZ", "Viewer.ViewpointF",
    "Viewer.imageViewScale",
];

fn assert_cameras(parsed: &Parsed, left: &EurocCamera, right: &EurocCamera) {
    assert_eq!(parsed.scalars["File.version"], "\"1.0\"");
    assert_eq!(parsed.scalars["Camera.type"], "\"PinHole\"");
    for (n, camera) in [(1, left), (2, right)] {
        let k = &camera.intrinsics;
        let d = &camera.distortion;
        let want = [k.fx, k.fy, k.cx, k.cy, d.k1, d.k2, d.p1, d.p2];
        for (key, want) in ["fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2"]
            .iter()
            .zip(want)
        {
            assert_eq!(
                parsed.real(&format!("Camera{n}.{key}")),
                want,
                "Camera{n}.{key}"
            );
        }
    }
    assert_eq!(parsed.int("Camera.width"), 752);
    assert_eq!(parsed.int("Camera.height"), 480);
    assert_eq!(parsed.int("Camera.fps"), 20);
    assert_eq!(parsed.int("Camera.RGB"), 0, "grey cameras");
    assert_eq!(parsed.real("Stereo.ThDepth"), 60.0);
    for key in ["nFeatures", "nLevels", "iniThFAST", "minThFAST"] {
        parsed.int(&format!("ORBextractor.{key}"));
    }
    parsed.real("ORBextractor.scaleFactor");
    for key in TRACKING_KEYS.iter().filter(|k| k.starts_with("Viewer.")) {
        parsed.real(key);
    }
}

#[test]
fn stereo_settings_of_mh01_match_orbslam3s_euroc_example() {
    let (cam0, cam1) = mh01_cameras();
    let parsed = parse(&stereo_settings(&cam0, &cam1));
    let keys: Vec<&str> = STEREO_KEYS.iter().chain(TRACKING_KEYS).copied().collect();
    assert_eq!(parsed.keys, keys);
    assert_cameras(&parsed, &cam0, &cam1);
    assert_matrix_close(
        &parsed.matrices["Stereo.T_c1_c2"],
        &ORBSLAM3_EUROC_T_C1_C2,
        "Stereo.T_c1_c2",
    );
}

#[test]
fn stereo_inertial_settings_of_mh01_match_orbslam3s_euroc_example() {
    let (cam0, cam1) = mh01_cameras();
    let imu = EurocImu::adis16448();
    let parsed = parse(&stereo_inertial_settings(&cam0, &cam1, &imu));
    let keys: Vec<&str> = STEREO_KEYS
        .iter()
        .chain(IMU_KEYS)
        .chain(TRACKING_KEYS)
        .copied()
        .collect();
    assert_eq!(parsed.keys, keys);
    assert_cameras(&parsed, &cam0, &cam1);
    assert_matrix_close(
        &parsed.matrices["Stereo.T_c1_c2"],
        &ORBSLAM3_EUROC_T_C1_C2,
        "Stereo.T_c1_c2",
    );
    // The body frame is the IMU's: T_b_c1 is cam0's T_BS, as in the example.
    assert_matrix_close(
        &parsed.matrices["IMU.T_b_c1"],
        &MH01_CAM0_T_BS,
        "IMU.T_b_c1",
    );
    // EuRoC's imu0/sensor.yaml densities (the example rounds NoiseGyro to 1.7e-4).
    assert_eq!(parsed.real("IMU.NoiseGyro"), 1.6968e-4);
    assert_eq!(parsed.real("IMU.NoiseAcc"), 2.0e-3);
    assert_eq!(parsed.real("IMU.GyroWalk"), 1.9393e-5);
    assert_eq!(parsed.real("IMU.AccWalk"), 3.0e-3);
    assert_eq!(parsed.real("IMU.Frequency"), 200.0);
}

#[test]
fn t_b_c1_maps_cam0_points_into_the_imu_frame_when_the_imu_is_not_the_body() {
    let (cam0, cam1) = mh01_cameras();
    let mut imu = EurocImu::adis16448();
    imu.body_from_imu = Pose::new(DQuat::from_rotation_y(0.4), DVec3::new(0.1, -0.2, 0.3));
    let parsed = parse(&stereo_inertial_settings(&cam0, &cam1, &imu));
    let m = &parsed.matrices["IMU.T_b_c1"];
    let p = DVec3::new(0.3, -0.7, 2.0);
    let mapped = DVec3::new(
        m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3],
        m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
        m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11],
    );
    // cam0 → body → IMU.
    let want = imu
        .body_from_imu
        .inverse()
        .transform_point(cam0.body_from_camera.transform_point(p));
    assert!((mapped - want).length() < 1e-12, "{mapped} {want}");
}

#[test]
fn rgb_cameras_say_so_and_mismatched_pairs_are_refused() {
    let (cam0, mut cam1) = mh01_cameras();
    assert_eq!(stereo_pair_problem(&cam0, &cam1), None);
    cam1.colour = CameraColour::Rgb;
    assert_eq!(parse(&stereo_settings(&cam0, &cam1)).int("Camera.RGB"), 1);

    cam1.intrinsics.width = 640;
    let problem = stereo_pair_problem(&cam0, &cam1).unwrap();
    assert!(
        problem.contains("752x480") && problem.contains("640x480"),
        "{problem}"
    );
    cam1.intrinsics.width = 752;
    cam1.rate_hz = 10.0;
    let problem = stereo_pair_problem(&cam0, &cam1).unwrap();
    assert!(
        problem.contains("20 Hz") && problem.contains("10 Hz"),
        "{problem}"
    );
}
