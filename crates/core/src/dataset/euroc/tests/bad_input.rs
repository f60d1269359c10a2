//! Bad inputs: each a one-line error naming the file (and the line, where there is one) and
//! what was expected.

use std::path::Path;

use super::fixture;
use super::published_format::write_published_style;
use crate::dataset::euroc::{read_euroc, EurocWriter, ImuSample};

/// Replaces `from` by `to` in `root/relative` (which must contain it).
fn edit(root: &Path, relative: &str, from: &str, to: &str) {
    let path = root.join(relative);
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains(from), "{relative} lacks {from:?}");
    std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
}

fn read_error(root: &Path) -> String {
    let error = read_euroc(root).unwrap_err().to_string();
    assert!(!error.contains('\n'), "one line: {error}");
    error
}

#[test]
fn bad_files_are_named_with_the_line_and_what_was_expected() {
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            "mav0/imu0/data.csv",
            "#timestamp [ns],w_RS_S_x",
            "#timestamp [ns],gx",
            "imu0/data.csv:1: expected the header '#timestamp [ns],w_RS_S_x [rad s^-1]",
        ),
        (
            "mav0/state_groundtruth_estimate0/data.csv",
            ",0.075593\n1403636580843555328",
            "\n1403636580843555328",
            "state_groundtruth_estimate0/data.csv:2: expected 17 comma-separated numbers",
        ),
        (
            "mav0/imu0/data.csv",
            "0.14032447186034408",
            "0.14O32",
            "imu0/data.csv:3: field 3 '0.14O32' is not a number",
        ),
        (
            // Found by the fuzzer: a carriage return inside a number broke the error in two.
            "mav0/imu0/data.csv",
            "0.14032447186034408",
            "0.14\r032",
            "imu0/data.csv:3: field 3 '0.14\\r032' is not a number",
        ),
        (
            "mav0/imu0/data.csv",
            "1403636579763555584,",
            "1403636579763555584.5,",
            "imu0/data.csv:3: field 1 '1403636579763555584.5' is not a timestamp in integer nanoseconds",
        ),
        (
            "mav0/imu0/data.csv",
            "1403636579763555584,",
            "1403636579758555392,",
            "imu0/data.csv:3: timestamp 1403636579758555392 ns does not come after",
        ),
        (
            "mav0/cam1/data.csv",
            "1403636579813555456.png",
            "1403636579813555999.png",
            "cam1/data.csv:3: names ",
        ),
        (
            "mav0/cam0/data.csv",
            "1403636579763555584.png",
            "../../imu0/data.csv",
            "cam0/data.csv:2: file name '../../imu0/data.csv': expected a plain name",
        ),
        (
            // Found by the fuzzer: a lone carriage return inside a name broke the error in two.
            "mav0/cam0/data.csv",
            "1403636579763555584.png",
            "1403636579763555584.png\r-1",
            "cam0/data.csv:2: file name '1403636579763555584.png\\r-1': expected a plain name",
        ),
        (
            "mav0/cam0/sensor.yaml",
            "rate_hz: 20\n",
            "",
            "cam0/sensor.yaml: missing key 'rate_hz'",
        ),
        (
            // Found by the property tests: a carriage return inside a key broke the error in two.
            "mav0/imu0/sensor.yaml",
            "  data:",
            "  dat\ra:",
            "imu0/sensor.yaml:9: key 'dat\\ra': expected letters, digits and '_'",
        ),
        (
            "mav0/imu0/sensor.yaml",
            "gyroscope_random_walk: 1.9393e-05",
            "gyroscope_random_walk: fast",
            "imu0/sensor.yaml:17: gyroscope_random_walk 'fast': expected a non-negative",
        ),
        (
            "mav0/cam0/sensor.yaml",
            "0.0, 0.0, 0.0, 1.0]",
            "0.0, 0.0, 0.0]",
            "cam0/sensor.yaml:9: expected 16 numbers (row-major 4x4 T_BS), found 15 fields",
        ),
        (
            "mav0/cam0/sensor.yaml",
            "0.0, 0.0, 0.0, 1.0]",
            "0.0, 0.0, 0.0, 1.0",
            "cam0/sensor.yaml:9: 'data': list opened with '[' is not closed",
        ),
        (
            "mav0/cam0/sensor.yaml",
            "resolution: [752, 480]",
            "resolution: [752.5, 480]",
            "cam0/sensor.yaml:16: resolution [752.5, 480]: expected two whole numbers",
        ),
        (
            "mav0/cam0/sensor.yaml",
            "distortion_model: radial-tangential",
            "distortion_model: equidistant",
            "cam0/sensor.yaml:19: distortion_model 'equidistant': expected 'radial-tangential'",
        ),
        (
            "mav0/cam0/sensor.yaml",
            "0.999557249008, 0.0149672133247",
            "1.999557249008, 0.0149672133247",
            "cam0/sensor.yaml:9: rotation block is not a rotation",
        ),
    ];
    for (file, from, to, expected) in cases {
        let dir = tempfile::tempdir().unwrap();
        write_published_style(dir.path());
        edit(dir.path(), file, from, to);
        let error = read_error(dir.path());
        assert!(
            error.contains(expected),
            "{file}: {error}\nexpected: {expected}"
        );
        assert!(
            error.starts_with(&dir.path().display().to_string()),
            "{error}"
        );
    }
}

#[test]
fn a_missing_sensor_yaml_or_layout_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let error = read_error(dir.path());
    assert!(
        error.contains("not a EuRoC dataset: expected a mav0/ folder"),
        "{error}"
    );
    write_published_style(dir.path());
    std::fs::remove_file(dir.path().join("mav0/cam1/sensor.yaml")).unwrap();
    let error = read_error(dir.path());
    assert!(error.contains("cam1/sensor.yaml: No such file"), "{error}");
}

#[test]
fn the_writer_refuses_time_going_back_naming_the_stream() {
    let dir = tempfile::tempdir().unwrap();
    let writer = EurocWriter::open(dir.path(), fixture::cameras(), Some(fixture::imu())).unwrap();
    writer.write_frame(1, 2.0, &fixture::image(0)).unwrap();
    writer.write_frame(0, 2.0, &fixture::image(0)).unwrap();
    // 2.0000000001 s rounds to the same nanosecond: not after.
    let error = writer
        .write_frame(1, 2.000_000_000_1, &fixture::image(0))
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("mav0/cam1: cam1: frame at 2000000000 ns does not come after the previous one at 2000000000 ns"),
        "{error}"
    );
    let error = writer
        .write_frame(0, f64::NAN, &fixture::image(0))
        .unwrap_err()
        .to_string();
    assert!(error.contains("cam0: frame time NaN s"), "{error}");
    let error = writer
        .write_frame(0, 3.0, &crate::RgbImage::new(5, 4))
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("cam0: 5x4 image: expected the camera's 6x4"),
        "{error}"
    );
    let error = writer
        .write_frame(2, 3.0, &fixture::image(0))
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("camera 2: there are only 2 cameras"),
        "{error}"
    );

    let samples = fixture::imu_samples();
    writer.write_imu(&samples[2..4]).unwrap();
    let error = writer.write_imu(&samples[..1]).unwrap_err().to_string();
    assert!(
        error.contains("imu0: IMU sample at 1403636579000000000 ns does not come after"),
        "{error}"
    );
    let twice = [samples[5], samples[5]];
    let error = writer.write_ground_truth(&[]).and_then(|_| {
        let gt = fixture::ground_truth();
        writer.write_ground_truth(&[gt[1], gt[0]])
    });
    let error = error.unwrap_err().to_string();
    assert!(
        error.contains("state_groundtruth_estimate0: ground-truth state at"),
        "{error}"
    );
    assert!(
        writer.write_imu(&twice).is_err(),
        "equal stamps are refused"
    );
}

#[test]
fn the_writer_refuses_symlinks_bad_names_and_an_absent_imu() {
    let dir = tempfile::tempdir().unwrap();
    let elsewhere = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(elsewhere.path(), dir.path().join("mav0")).unwrap();
    let error = EurocWriter::open(dir.path(), fixture::cameras(), None)
        .err()
        .unwrap()
        .to_string();
    assert!(
        error.contains("mav0: is a symbolic link inside the output folder"),
        "{error}"
    );

    let dir = tempfile::tempdir().unwrap();
    let mut cameras = fixture::cameras();
    cameras[1].name = "../cam1".into();
    let error = EurocWriter::open(dir.path(), cameras, None)
        .err()
        .unwrap()
        .to_string();
    assert!(
        error.contains("camera name '../cam1': expected a folder name"),
        "{error}"
    );
    let mut cameras = fixture::cameras();
    cameras[1].name = "cam0".into();
    let error = EurocWriter::open(dir.path(), cameras, None)
        .err()
        .unwrap()
        .to_string();
    assert!(
        error.contains("camera name 'cam0' is given twice"),
        "{error}"
    );
    let mut cameras = fixture::cameras();
    cameras[1].intrinsics.height = 8;
    let error = EurocWriter::open(dir.path(), cameras, None)
        .err()
        .unwrap()
        .to_string();
    assert!(
        error.contains("orbslam3_stereo.yaml: cam0 is 6x4 and cam1 is 6x8: ORB-SLAM3's stereo settings need one resolution"),
        "{error}"
    );

    let writer = EurocWriter::open(dir.path(), fixture::cameras(), None).unwrap();
    let sample = ImuSample {
        t_ns: 1,
        gyro: glam::DVec3::ZERO,
        accel: glam::DVec3::ZERO,
    };
    let error = writer.write_imu(&[sample]).unwrap_err().to_string();
    assert!(error.contains("opened without an IMU"), "{error}");
    for name in ["../x.csv", "mav0", "", ".hidden", "a/b.csv"] {
        let error = writer.write_record(name, b"x").unwrap_err().to_string();
        assert!(
            error.contains("expected a plain file name"),
            "{name}: {error}"
        );
    }
    writer
        .write_record("calibration_per_frame.csv", b"x")
        .unwrap();
    assert!(dir.path().join("calibration_per_frame.csv").is_file());
}
