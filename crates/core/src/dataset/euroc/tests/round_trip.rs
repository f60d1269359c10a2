use super::fixture::{self, START_NS};
use crate::dataset::euroc::{nanoseconds_from_seconds, read_euroc, CameraColour};
use crate::dataset::{decode_rgb, MANIFEST_FILE};
use crate::Pose;

/// Largest difference of a pose entry after writing and reading (shortest round-trip digits;
/// the rotation goes through a 3×3 matrix in sensor.yaml).
const POSE_TOLERANCE: f64 = 1e-9;

fn assert_poses_close(a: &Pose, b: &Pose, what: &str) {
    let (a, b) = (a.to_row_major(), b.to_row_major());
    let worst = a
        .iter()
        .zip(&b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(worst < POSE_TOLERANCE, "{what}: {worst:e}\n{a:?}\n{b:?}");
}

#[test]
fn a_written_dataset_reads_back_equal() {
    let dir = tempfile::tempdir().unwrap();
    let times = fixture::write(dir.path());
    assert!(dir.path().join(MANIFEST_FILE).is_file(), "manifest last");
    let read = read_euroc(dir.path()).unwrap();
    assert_eq!(read.mav_dir, dir.path().join("mav0"));

    // Near 1.4e9 s an f64 resolves about 240 ns: the stamps are the nearest nanosecond of the
    // f64 times, and those come back exactly.
    for (j, t) in times.iter().enumerate() {
        let t_s = fixture::START_S + j as f64 / fixture::CAMERA_RATE_HZ;
        assert_eq!(Some(*t), nanoseconds_from_seconds(t_s));
        assert!(t.abs_diff(START_NS + j as u64 * 50_000_000) < 240, "{t}");
    }
    let written = fixture::cameras();
    assert_eq!(read.cameras.len(), 2);
    for (c, (got, want)) in read.cameras.iter().zip(&written).enumerate() {
        let camera = &got.camera;
        assert_eq!(camera.name, want.name);
        assert_eq!(camera.comment, want.comment);
        assert_eq!(camera.rate_hz, want.rate_hz);
        assert_eq!(camera.intrinsics, want.intrinsics);
        assert_eq!(camera.distortion, want.distortion);
        assert_eq!(camera.colour, want.colour);
        assert_poses_close(&camera.body_from_camera, &want.body_from_camera, &want.name);
        let frame_times: Vec<u64> = got.frames.iter().map(|f| f.t_ns).collect();
        assert_eq!(frame_times, times);
        for (j, frame) in got.frames.iter().enumerate() {
            let dir = dir.path().join(format!("mav0/{}/data", want.name));
            assert_eq!(frame.path, dir.join(format!("{}.png", times[j])));
            let bytes = std::fs::read(&frame.path).unwrap();
            let decoded = image::load_from_memory(&bytes).unwrap();
            let sent = fixture::image(2 * j + c);
            match want.colour {
                CameraColour::Rgb => assert_eq!(decode_rgb(&bytes).unwrap(), sent, "lossless"),
                CameraColour::Grey => {
                    assert_eq!(decoded.color(), image::ColorType::L8);
                    let luma = decoded.into_luma8().into_raw();
                    let first = sent.pixel(0, 0).map(f64::from);
                    let expected = (0.299 * first[0] + 0.587 * first[1] + 0.114 * first[2]).round();
                    assert_eq!(luma[0] as f64, expected);
                }
                CameraColour::Grey16 => unreachable!("the fixture's cameras are 8-bit"),
            }
        }
    }

    let imu = read.imu.expect("imu0");
    assert_eq!(
        imu.imu,
        fixture::imu(),
        "the identity T_BS reads back exactly"
    );
    assert_eq!(
        imu.samples,
        fixture::imu_samples(),
        "shortest round-trip digits are exact"
    );

    let truth = read.ground_truth.expect("ground truth");
    let want = fixture::ground_truth();
    assert_eq!(truth.len(), want.len());
    for (got, want) in truth.iter().zip(&want) {
        assert_eq!(got.t_ns, want.t_ns);
        assert_poses_close(&got.world_from_body, &want.world_from_body, "ground truth");
        let dq = got.world_from_body.rotation - want.world_from_body.rotation;
        assert!(
            dq.length() < POSE_TOLERANCE,
            "same quaternion, same sign: {dq:?}"
        );
        assert_eq!(
            (got.velocity, got.gyro_bias, got.accel_bias),
            (want.velocity, want.gyro_bias, want.accel_bias)
        );
    }
}

#[test]
fn a_dataset_without_ground_truth_or_imu_reads_as_such() {
    let dir = tempfile::tempdir().unwrap();
    let writer =
        crate::dataset::euroc::EurocWriter::open(dir.path(), fixture::cameras(), None).unwrap();
    writer.write_frame(0, 0.5, &fixture::image(0)).unwrap();
    writer.finish(fixture::manifest()).unwrap();
    let read = read_euroc(&dir.path().join("mav0")).unwrap();
    assert_eq!(read.imu, None);
    assert_eq!(read.ground_truth, None);
    assert_eq!(read.cameras[0].frames.len(), 1);
    assert_eq!(read.cameras[0].frames[0].t_ns, 500_000_000);
    assert!(read.cameras[1].frames.is_empty());
    assert_eq!(
        read.cameras[1].camera.colour,
        CameraColour::Grey,
        "no frame to tell from"
    );
}

/// Which of the two ORB-SLAM3 settings files a dataset root holds, each checked to be in the
/// checksum list (written through the hashed path).
fn orbslam3_files(root: &std::path::Path) -> Vec<&'static str> {
    use crate::dataset::euroc::{ORBSLAM3_STEREO_FILE, ORBSLAM3_STEREO_INERTIAL_FILE};
    let listed = crate::dataset::Checksums::read(root).unwrap();
    [ORBSLAM3_STEREO_FILE, ORBSLAM3_STEREO_INERTIAL_FILE]
        .into_iter()
        .filter(|name| {
            let present = root.join(name).is_file();
            assert_eq!(
                present,
                listed.paths().any(|p| p == *name),
                "{name}: on disk exactly when hashed"
            );
            present
        })
        .collect()
}

#[test]
fn orbslam3_stereo_settings_come_with_two_cameras_and_inertial_ones_with_an_imu_too() {
    let dir = tempfile::tempdir().unwrap();
    fixture::write(dir.path());
    assert_eq!(
        orbslam3_files(dir.path()),
        ["orbslam3_stereo.yaml", "orbslam3_stereo_inertial.yaml"]
    );
    let inertial =
        std::fs::read_to_string(dir.path().join("orbslam3_stereo_inertial.yaml")).unwrap();
    assert!(
        inertial.contains("\nIMU.T_b_c1: !!opencv-matrix\n"),
        "{inertial}"
    );
    assert!(inertial.contains("\nCamera2.fx: 458.654\n"), "{inertial}");
    assert!(
        read_euroc(dir.path()).is_ok(),
        "the reader takes the root with them"
    );

    let rigs = [
        (fixture::cameras(), None, vec!["orbslam3_stereo.yaml"]),
        (
            fixture::cameras()[..1].to_vec(),
            Some(fixture::imu()),
            vec![],
        ),
        (fixture::cameras()[..1].to_vec(), None, vec![]),
    ];
    for (cameras, imu, want) in rigs {
        let dir = tempfile::tempdir().unwrap();
        let what = format!("{} cameras, imu {}", cameras.len(), imu.is_some());
        let writer = crate::dataset::euroc::EurocWriter::open(dir.path(), cameras, imu).unwrap();
        writer.finish(fixture::manifest()).unwrap();
        assert_eq!(orbslam3_files(dir.path()), want, "{what}");
    }
}

#[test]
fn recorded_nanosecond_stamps_and_copied_files_are_kept_exactly() {
    // EuRoC's published stamps went through doubles (multiples of 256 ns) and happen to survive
    // f64 seconds; a stamp of any nanosecond (TUM-VI's are) does not: f64 resolves ~240 ns at
    // 1.4e9 s.
    const PUBLISHED_NS: u64 = 1_403_636_579_763_555_584;
    const ANY_NS: u64 = 1_403_636_579_863_555_555;
    assert_eq!(
        nanoseconds_from_seconds(PUBLISHED_NS as f64 / 1e9),
        Some(PUBLISHED_NS)
    );
    assert_ne!(nanoseconds_from_seconds(ANY_NS as f64 / 1e9), Some(ANY_NS));
    let dir = tempfile::tempdir().unwrap();
    let writer = crate::dataset::euroc::EurocWriter::open(
        dir.path(),
        fixture::cameras(),
        Some(fixture::imu()),
    )
    .unwrap();
    for c in 0..2 {
        for t_ns in [PUBLISHED_NS, ANY_NS] {
            writer.write_frame_ns(c, t_ns, &fixture::image(c)).unwrap();
        }
    }
    let imu_csv = "#timestamp [ns],w\r\n1403636579758555392,-0.099134701513277898\r\n";
    let gt_csv = "#timestamp, p_RS_R_x [m]\n1403636580838555648,4.688319\n";
    writer
        .copy_sensor_file("imu0", "data.csv", imu_csv.as_bytes())
        .unwrap();
    writer
        .copy_sensor_file("state_groundtruth_estimate0", "data.csv", gt_csv.as_bytes())
        .unwrap();
    writer
        .copy_sensor_file("cam1", "sensor.yaml", b"# mine\n")
        .unwrap();
    for (sensor, file) in [
        ("cam0", "data.csv"),
        ("../x", "sensor.yaml"),
        ("imu0", "x.txt"),
    ] {
        let err = writer
            .copy_sensor_file(sensor, file, b"")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("expected a camera's or imu0's sensor.yaml"),
            "{err}"
        );
    }
    writer.finish(fixture::manifest()).unwrap();
    let mav = dir.path().join("mav0");
    let read = |rel: &str| std::fs::read_to_string(mav.join(rel)).unwrap();
    assert_eq!(read("imu0/data.csv"), imu_csv);
    assert_eq!(read("state_groundtruth_estimate0/data.csv"), gt_csv);
    assert_eq!(read("cam1/sensor.yaml"), "# mine\n");
    assert!(read("cam0/sensor.yaml").starts_with("# General sensor definitions."));
    assert!(read("imu0/sensor.yaml").starts_with("#Default imu sensor yaml file"));
    assert_eq!(
        read("cam0/data.csv"),
        format!(
            "#timestamp [ns],filename\n{PUBLISHED_NS},{PUBLISHED_NS}.png\n{ANY_NS},{ANY_NS}.png\n"
        )
    );
    assert!(mav.join(format!("cam1/data/{ANY_NS}.png")).is_file());
}

#[test]
fn copied_frames_keep_their_bytes_and_their_order() {
    let dir = tempfile::tempdir().unwrap();
    let writer =
        crate::dataset::euroc::EurocWriter::open(dir.path(), fixture::cameras(), None).unwrap();
    let png = b"\x89PNG not decoded, copied";
    writer.copy_frame_ns(0, 2_000, png).unwrap();
    writer.write_frame_ns(0, 3_000, &fixture::image(0)).unwrap();
    let err = writer.copy_frame_ns(0, 2_500, png).unwrap_err().to_string();
    assert!(
        err.contains("does not come after the previous one at 3000 ns"),
        "{err}"
    );
    writer.finish(fixture::manifest()).unwrap();
    let mav = dir.path().join("mav0");
    assert_eq!(std::fs::read(mav.join("cam0/data/2000.png")).unwrap(), png);
    assert_eq!(
        std::fs::read_to_string(mav.join("cam0/data.csv")).unwrap(),
        "#timestamp [ns],filename\n2000,2000.png\n3000,3000.png\n"
    );
}
