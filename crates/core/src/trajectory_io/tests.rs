use std::path::{Path, PathBuf};

use glam::{DQuat, DVec3};

use super::*;
use crate::{CoreError, Pose, Trajectory};

const EPS: f64 = 1e-12;

struct Dir(tempfile::TempDir);

impl Dir {
    fn new() -> Self {
        Self(tempfile::tempdir().expect("temp dir"))
    }

    fn write(&self, name: &str, contents: impl AsRef<[u8]>) -> PathBuf {
        let path = self.0.path().join(name);
        std::fs::write(&path, contents).expect("write fixture");
        path
    }
}

fn read(path: &Path) -> TrajectoryFile {
    read_trajectory(path, None).unwrap_or_else(|e| panic!("{e}"))
}

/// The full error message of reading `contents` (auto-detected unless `format` is given),
/// with the temp dir's path replaced by `F`.
fn error_of(contents: &str, format: Option<TrajectoryFormat>) -> String {
    let dir = Dir::new();
    let path = dir.write("traj.txt", contents);
    let err = read_trajectory(&path, format).expect_err("reading should fail");
    err.to_string().replace(&path.display().to_string(), "F")
}

fn sample_poses() -> Vec<Pose> {
    (0..5)
        .map(|i| {
            let a = i as f64 * 0.37;
            Pose::new(
                DQuat::from_euler(glam::EulerRot::ZYX, a, -0.5 * a, 0.2 + a),
                DVec3::new(a.sin() * 3.0, 1.0 / 3.0 + a, -a * 1e-7),
            )
        })
        .collect()
}

#[test]
fn tum_is_lenient_on_whitespace_comments_bom_and_crlf() {
    let dir = Dir::new();
    let path = dir.write(
        "gt.txt",
        "\u{feff}# ground truth\r\n#  timestamp tx ty tz qx qy qz qw\r\n\
         1.5\t0.1  0.2 0.3   0 0 0 1   \r\n\r\n   2.25 1 2 3 0 0 0.7071067811865476 0.7071067811865476\t\r\n",
    );
    let file = read(&path);
    assert_eq!(file.format, TrajectoryFormat::Tum);
    assert_eq!(file.time_source, TimeSource::File);
    assert_eq!(file.trajectory.timestamps, vec![1.5, 2.25]);
    assert_eq!(
        file.trajectory.poses[0].translation,
        DVec3::new(0.1, 0.2, 0.3)
    );
    let expected = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
    assert!(file.trajectory.poses[1].rotation.angle_between(expected) < 1e-9);
}

#[test]
fn non_unit_quaternions_are_normalised() {
    let dir = Dir::new();
    let path = dir.write("gt.txt", "0 0 0 0 0 0 2 2\n1 0 0 0 1e-3 0 0 0.5\n");
    for pose in read(&path).trajectory.poses {
        assert!((pose.rotation.length() - 1.0).abs() < EPS);
    }
}

#[test]
fn tum_wrong_field_count_names_the_line() {
    assert_eq!(
        error_of("# c\n0 0 0 0 0 0 0 1\n1 0 0 0 0 0 1\n", None),
        "F:3: expected 8 numbers 't tx ty tz qx qy qz qw', found 7 fields"
    );
}

#[test]
fn a_word_where_a_number_belongs_names_field_and_line() {
    assert_eq!(
        error_of("0 0 0 0 0 0 0 1\n1 0 abc 0 0 0 0 1\n", None),
        "F:2: field 3 'abc' is not a number (expected 8 numbers 't tx ty tz qx qy qz qw')"
    );
}

#[test]
fn nan_and_infinity_are_errors_naming_the_line() {
    assert_eq!(
        error_of("0 0 0 0 0 0 0 1\n1 NaN 0 0 0 0 0 1\n", None),
        "F:2: field 2 is 'NaN'; expected a finite number"
    );
    assert_eq!(
        error_of("0 0 0 inf 0 0 0 1\n", None),
        "F:1: field 4 is 'inf'; expected a finite number"
    );
}

#[test]
fn zero_quaternion_is_an_error_on_its_line() {
    assert_eq!(
        error_of("0 0 0 0 0 0 0 1\n\n1 0 0 0 0 0 0 0\n", None),
        "F:3: zero quaternion (qx qy qz qw all 0); expected a rotation"
    );
}

/// Finite components whose squares overflow gave a zero "unit" quaternion, then NaN poses.
#[test]
fn quaternion_too_large_to_normalise_is_an_error_not_a_nan_pose() {
    assert_eq!(
        error_of("0 0 0 0 1e200 0 0 1e200\n", None),
        "F:1: quaternion (1e200 0e0 0e0 1e200) cannot be normalised in 64-bit floats; expected a rotation"
    );
    assert_eq!(
        error_of("1403636579758555392,1,2,3,1e300,0,0,0\n", None),
        "F:1: quaternion (0e0 0e0 0e0 1e300) cannot be normalised in 64-bit floats; expected a rotation"
    );
}

#[test]
fn more_poses_than_the_limit_is_an_error_before_parsing() {
    let text = "0 0 0 0 0 0 0 1\n".repeat(crate::limits::MAX_POSES + 1);
    assert_eq!(
        error_of(&text, None),
        format!(
            "F:{}: more than {} poses, the most a trajectory may hold",
            crate::limits::MAX_POSES + 1,
            crate::limits::MAX_POSES
        )
    );
}

#[test]
fn empty_or_comment_only_file_has_no_poses() {
    let expected = "F: no poses (the file is empty or only comments)";
    assert_eq!(error_of("", None), expected);
    assert_eq!(error_of("# only\n# comments\n\n", None), expected);
    assert_eq!(error_of("", Some(TrajectoryFormat::Tum)), expected);
}

#[test]
fn undetectable_field_count_is_an_error() {
    assert_eq!(
        error_of("# x\n1 2 3\n", None),
        "F:2: cannot tell the trajectory format from 3 fields: expected 8 numbers (TUM), \
         12 (KITTI), 16 (Replica), comma-separated EuRoC or a COLMAP images.txt line; or \
         force a format"
    );
}

#[test]
fn forcing_a_format_checks_every_line_against_it() {
    assert_eq!(
        error_of("0 0 0 0 0 0 0 1\n", Some(TrajectoryFormat::Kitti)),
        "F:1: expected 12 numbers (row-major 3x4 camera-to-world), found 8 fields"
    );
}

#[test]
fn missing_file_and_binary_file_are_errors_naming_the_path() {
    let dir = Dir::new();
    let missing = dir.0.path().join("nope.txt");
    let err = read_trajectory(&missing, None).unwrap_err();
    assert!(matches!(err, CoreError::Io { .. }));
    assert!(err.to_string().starts_with(&missing.display().to_string()));

    let binary = dir.write("bin.txt", [0x30, 0x20, 0xff, 0xfe, 0x0a]);
    let err = read_trajectory(&binary, None).unwrap_err().to_string();
    assert!(
        err.ends_with(
            "not a text file (invalid UTF-8 at byte 2); expected a trajectory in text form"
        ),
        "{err}"
    );
}

#[test]
fn replica_frames_are_stamped_at_the_rate() {
    let dir = Dir::new();
    let traj = Trajectory::from_poses_at_rate(sample_poses(), 20.0);
    let path = dir.write("traj.txt", "");
    write_replica(&path, &traj).unwrap();
    let file = read(&path);
    assert_eq!(file.format, TrajectoryFormat::Replica);
    assert_eq!(file.time_source, TimeSource::Rate { hz: 20.0 });
    assert_eq!(file.trajectory.timestamps, vec![0.0, 0.05, 0.1, 0.15, 0.2]);

    let options = ReadOptions {
        replica_rate_hz: 30.0,
        ..ReadOptions::default()
    };
    let at_30 = read_trajectory_with(&path, &options).unwrap();
    assert_eq!(at_30.trajectory.timestamps[3], 3.0 / 30.0);
}

#[test]
fn replica_round_trips_every_matrix_bit_for_bit() {
    let dir = Dir::new();
    let traj = Trajectory::from_poses_at_rate(sample_poses(), 20.0);
    let path = dir.write("traj.txt", "");
    write_replica(&path, &traj).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    for (line, pose) in text.lines().zip(&traj.poses) {
        let written: Vec<f64> = line.split(' ').map(|v| v.parse().unwrap()).collect();
        assert_eq!(written, pose.to_row_major().to_vec());
    }
    for (back, pose) in read(&path).trajectory.poses.iter().zip(&traj.poses) {
        assert!((back.translation - pose.translation).length() < EPS);
        assert!(back.rotation.angle_between(pose.rotation) < 1e-7);
        assert!((back.rotation.dot(pose.rotation).abs() - 1.0).abs() < EPS);
    }
}

#[test]
fn replica_rejects_a_bad_last_row_and_a_scaled_rotation() {
    let identity_with_bad_row = "1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1\n";
    assert_eq!(
        error_of(identity_with_bad_row, None),
        "F:1: last matrix row is [0.0, 0.0, 1.0, 1.0]; expected 0 0 0 1 (a rigid 4x4 transform)"
    );
    let scaled = "2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1\n";
    assert_eq!(
        error_of(scaled, None),
        "F:1: rotation block is not a rotation (max |RᵀR − I| = 3.00e0, det = 8.000000); \
         expected a rigid transform"
    );
    let mirrored = "-1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n";
    assert!(error_of(mirrored, None).contains("det = -1.000000"));
}

#[test]
fn replica_rate_must_be_positive() {
    let dir = Dir::new();
    let path = dir.write("traj.txt", "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n");
    let options = ReadOptions {
        replica_rate_hz: 0.0,
        ..ReadOptions::default()
    };
    let err = read_trajectory_with(&path, &options).unwrap_err();
    assert_eq!(
        err.to_string(),
        "frame rate 0 Hz: expected a positive number"
    );
}

#[test]
fn kitti_without_times_is_indexed_and_with_times_is_stamped() {
    let dir = Dir::new();
    let lines: String = sample_poses()
        .iter()
        .map(|p| {
            let m = p.to_row_major();
            let row: Vec<String> = m[..12].iter().map(|v| format!("{v:e}")).collect();
            row.join(" ") + "\n"
        })
        .collect();
    let path = dir.write("00.txt", &lines);
    let file = read(&path);
    assert_eq!(file.format, TrajectoryFormat::Kitti);
    assert_eq!(file.time_source, TimeSource::FrameIndex);
    assert_eq!(file.trajectory.timestamps, vec![0.0, 1.0, 2.0, 3.0, 4.0]);
    for (back, pose) in file.trajectory.poses.iter().zip(sample_poses()) {
        assert!((back.translation - pose.translation).length() < EPS);
        assert!(back.rotation.angle_between(pose.rotation) < 1e-7);
    }

    let times = dir.write("times.txt", "0.0\n1.03e-1\n0.2\n0.31\n0.4\n");
    let options = ReadOptions {
        kitti_times: Some(times.clone()),
        ..ReadOptions::default()
    };
    let stamped = read_trajectory_with(&path, &options).unwrap();
    assert_eq!(stamped.time_source, TimeSource::File);
    assert_eq!(stamped.trajectory.timestamps[1], 0.103);

    std::fs::write(&times, "0\n1\n").unwrap();
    let err = read_trajectory_with(&path, &options)
        .unwrap_err()
        .to_string();
    assert_eq!(
        err,
        format!(
            "{}: 2 timestamps, but {} has 5 poses; expected one timestamp per pose",
            times.display(),
            path.display()
        )
    );
}

#[test]
fn euroc_reads_nanoseconds_and_w_first_quaternions() {
    let dir = Dir::new();
    let path = dir.write(
        "data.csv",
        "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z [], v_x\n\
         1403636579758555392,4.688319,-1.786938,0.783338,0.534108,-0.153029,-0.827383,-0.082152,0.1\n\
         1403636579763555584, 4.688general\n",
    );
    let err = read_trajectory(&path, None).unwrap_err().to_string();
    assert!(err.ends_with(":3: expected at least 8 comma-separated numbers 't[ns],px,py,pz,qw,qx,qy,qz', found 2 fields"), "{err}");

    std::fs::write(
        &path,
        "#timestamp,x,y,z,qw,qx,qy,qz\n1403636579758555392, 4.688319,-1.786938,0.783338,1,0,0,0\n\
         1403636579763555584,1,2,3,0.5,0.5,0.5,0.5\n",
    )
    .unwrap();
    let file = read(&path);
    assert_eq!(file.format, TrajectoryFormat::Euroc);
    assert_eq!(file.trajectory.timestamps[0], 1403636579758555392.0 / 1e9);
    assert_eq!(file.trajectory.poses[0].rotation, DQuat::IDENTITY);
    let q = file.trajectory.poses[1].rotation;
    assert_eq!([q.w, q.x, q.y, q.z], [0.5, 0.5, 0.5, 0.5]);
}

#[test]
fn tum_round_trips_with_six_decimal_stamps_and_three_header_lines() {
    let dir = Dir::new();
    let traj = Trajectory::new(vec![0.0, 1.0 / 3.0, 1e9 + 0.5, 7.0, 8.25], sample_poses());
    let path = dir.write("groundtruth.txt", "");
    write_tum(&path, &traj).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[..3].iter().all(|l| l.starts_with('#')));
    assert!(lines[4].starts_with("0.333333 "), "{}", lines[4]);
    assert!(lines[5].starts_with("1000000000.500000 "), "{}", lines[5]);

    let back = read(&path).trajectory;
    assert_eq!(back.timestamps[1], 0.333333);
    for (b, p) in back.poses.iter().zip(&traj.poses) {
        assert_eq!(b.translation, p.translation);
        assert!((b.rotation.dot(p.rotation) - 1.0).abs() < EPS);
    }
}

/// `images.txt` as COLMAP writes it: a comment header, ids in another order than the names, each
/// image line followed by its 2D points (one of them empty, one a long line).
fn colmap_images_txt(poses: &[Pose]) -> String {
    let mut text = String::from(
        "# Image list with two lines of data per image:\n\
         #   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n\
         #   POINTS2D[] as (X, Y, POINT3D_ID)\n\
         # Number of images: 5, mean observations per image: 2\n",
    );
    for (k, i) in [3usize, 0, 4, 1, 2].into_iter().enumerate() {
        let world_to_camera = poses[i].inverse();
        let (q, t) = (world_to_camera.rotation, world_to_camera.translation);
        text.push_str(&format!(
            "{} {:.17e} {:.17e} {:.17e} {:.17e} {:.17e} {:.17e} {:.17e} 1 frame_{i:05}.png\n",
            k + 7,
            q.w,
            q.x,
            q.y,
            q.z,
            t.x,
            t.y,
            t.z
        ));
        match k {
            1 => text.push('\n'),
            2 => text.push_str("12.5 40.25 -1 ".repeat(400).trim_end()),
            _ => text.push_str("100.5 20.25 17 3.5 4.5 -1"),
        }
        text.push('\n');
    }
    text
}

#[test]
fn colmap_images_are_camera_to_world_in_name_order_stamped_at_the_rate() {
    let dir = Dir::new();
    let poses = sample_poses();
    let path = dir.write("images.txt", colmap_images_txt(&poses));
    let file = read_trajectory_with(
        &path,
        &ReadOptions {
            replica_rate_hz: 10.0,
            ..ReadOptions::default()
        },
    )
    .unwrap();
    assert_eq!(file.format, TrajectoryFormat::Colmap);
    assert_eq!(file.time_source, TimeSource::Rate { hz: 10.0 });
    assert_eq!(file.trajectory.timestamps, [0.0, 0.1, 0.2, 0.3, 0.4]);
    for (read, expected) in file.trajectory.poses.iter().zip(&poses) {
        assert!((read.translation - expected.translation).length() < EPS);
        assert!(read.rotation.angle_between(expected.rotation) < 1e-9);
    }
    // The camera centre is −Rᵀt: a camera at the origin looking along +x reads back so.
    let looking_x = Pose::new(
        DQuat::from_mat3(&glam::DMat3::from_cols(
            DVec3::NEG_Y,
            DVec3::NEG_Z,
            DVec3::X,
        )),
        DVec3::new(1.0, 2.0, 3.0),
    );
    let one = dir.write("one.txt", colmap_images_txt(&[looking_x; 5]));
    let read_one = read(&one).trajectory.poses[0];
    assert!((read_one.translation - DVec3::new(1.0, 2.0, 3.0)).length() < EPS);
    assert!((read_one.rotation * DVec3::Z - DVec3::X).length() < EPS);
}

#[test]
fn colmap_errors_name_the_line() {
    let line = "1 1 0 0 0 0 0 0 1 a.png\n\n";
    let twice = format!("{line}{line}");
    assert_eq!(
        error_of(&twice, None),
        "F:3: image 'a.png' again (first on line 1); expected each image once"
    );
    let cut = format!("{line}2 1 0 0 0 0 0\n");
    let err = error_of(&cut, Some(TrajectoryFormat::Colmap));
    assert!(
        err.starts_with("F:3: expected an image line 'IMAGE_ID QW"),
        "{err}"
    );
    let nan = "1 nan 0 0 0 0 0 0 1 a.png\n\n";
    assert!(
        error_of(nan, None).starts_with("F:1: field 1 is 'nan'"),
        "{}",
        error_of(nan, None)
    );
    let zero = "1 0 0 0 0 0 0 0 1 a.png\n\n";
    assert!(error_of(zero, None).contains("F:1: zero quaternion"));
}
