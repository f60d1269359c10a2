use std::path::{Path, PathBuf};

use glam::{DMat3, DVec3};

use super::*;

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Row-major 4×4 numbers of a camera-to-world transform with OpenGL camera axes.
fn gl_rows(rotation: DMat3, position: DVec3) -> Vec<f64> {
    let r = rotation.to_cols_array_2d();
    (0..3)
        .flat_map(|row| [r[0][row], r[1][row], r[2][row], position[row]])
        .chain([0.0, 0.0, 0.0, 1.0])
        .collect()
}

fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).length() < 1e-9
}

#[test]
fn a_camera_path_reads_with_opencv_axes_at_its_fps() {
    let dir = tempfile::tempdir().unwrap();
    // An OpenGL camera with identity rotation looks down world -z, its up along world +y.
    let cameras: Vec<String> = (0..3)
        .map(|i| {
            let rows = gl_rows(DMat3::IDENTITY, DVec3::new(i as f64, 0.5, 2.0));
            format!("{{\"camera_to_world\": {rows:?}, \"fov\": 60, \"aspect\": 1.5}}")
        })
        .collect();
    let text = format!(
        "{{\"render_height\": 480, \"fps\": 24, \"camera_path\": [{}]}}",
        cameras.join(",")
    );
    let path = write(dir.path(), "camera_path.json", &text);
    let file = crate::trajectory_io::read_trajectory(&path, None).unwrap();
    assert_eq!(file.format, super::super::TrajectoryFormat::Nerfstudio);
    let t = &file.trajectory;
    assert_eq!(t.len(), 3);
    assert!((t.timestamps[2] - 2.0 / 24.0).abs() < 1e-12);
    let pose = t.poses[1];
    assert!(close(pose.translation, DVec3::new(1.0, 0.5, 2.0)));
    // OpenCV axes: forward (camera +z) is world -z, down (camera +y) is world -y.
    assert!(close(pose.rotation * DVec3::Z, DVec3::NEG_Z));
    assert!(close(pose.rotation * DVec3::Y, DVec3::NEG_Y));
    assert!(close(pose.rotation * DVec3::X, DVec3::X));
}

#[test]
fn a_transforms_json_moves_by_the_dataparser_transform_in_name_order() {
    let dir = tempfile::tempdir().unwrap();
    let turn = DMat3::from_rotation_y(0.3);
    let frames = [
        ("images/frame_00002.png", 2.0),
        ("images/frame_00001.png", 1.0),
    ]
    .map(|(name, x)| {
        let rows = gl_rows(turn, DVec3::new(x, 0.0, 0.0));
        let matrix: Vec<Vec<f64>> = rows.chunks(4).map(<[f64]>::to_vec).collect();
        format!("{{\"file_path\": \"{name}\", \"transform_matrix\": {matrix:?}}}")
    });
    let text = format!("{{\"fl_x\": 500, \"frames\": [{}]}}", frames.join(","));
    let path = write(dir.path(), "transforms.json", &text);
    // The dataparser: a quarter turn about z, a shift, then half the size.
    let quarter = DMat3::from_rotation_z(std::f64::consts::FRAC_PI_2);
    let moved = gl_rows(quarter, DVec3::new(1.0, 2.0, 3.0));
    let transform: Vec<Vec<f64>> = moved.chunks(4).take(3).map(<[f64]>::to_vec).collect();
    let dataparser = write(
        dir.path(),
        "dataparser_transforms.json",
        &format!("{{\"transform\": {transform:?}, \"scale\": 0.5}}"),
    );
    let text = std::fs::read_to_string(&path).unwrap();
    let t = parse(&path, &text, 10.0, Some(&dataparser)).unwrap();
    assert_eq!(t.len(), 2);
    // Frame 1 first: at x = 1, turned a quarter (to y = 1), shifted, halved.
    let expected = 0.5 * (quarter * DVec3::new(1.0, 0.0, 0.0) + DVec3::new(1.0, 2.0, 3.0));
    assert!(
        close(t.poses[0].translation, expected),
        "{}",
        t.poses[0].translation
    );
    let forward = t.poses[0].rotation * DVec3::Z;
    assert!(close(forward, quarter * (turn * DVec3::NEG_Z)), "{forward}");
    assert!((t.timestamps[1] - 0.1).abs() < 1e-12);
    // The rotation is a rotation: the scale moves positions only.
    assert!((t.poses[1].rotation.length() - 1.0).abs() < 1e-12);
}

#[test]
fn bad_nerfstudio_files_name_the_file_and_the_entry() {
    let dir = tempfile::tempdir().unwrap();
    let short = write(
        dir.path(),
        "short.json",
        "{\"camera_path\": [{\"camera_to_world\": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}, {\"camera_to_world\": [1,0,0]}]}",
    );
    let err = crate::trajectory_io::read_trajectory(&short, None)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("short.json") && err.contains("camera_path[1].camera_to_world"),
        "{err}"
    );

    let neither = write(dir.path(), "neither.json", "{\"cameras\": []}");
    let err = crate::trajectory_io::read_trajectory(&neither, None)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("'camera_path'") && err.contains("'frames'"),
        "{err}"
    );

    let path = write(dir.path(), "path.json", "{\"camera_path\": []}");
    let dataparser = write(
        dir.path(),
        "dp.json",
        "{\"transform\": [[1,0,0,0],[0,1,0,0],[0,0,1,0]], \"scale\": 1}",
    );
    let err = parse(&path, "{\"camera_path\": []}", 10.0, Some(&dataparser))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("camera path") && err.contains("dataparser"),
        "{err}"
    );

    let frames = "{\"frames\": [{\"file_path\": \"a\", \"transform_matrix\": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}]}";
    let no_scale = write(
        dir.path(),
        "no_scale.json",
        "{\"transform\": [[1,0,0,0],[0,1,0,0],[0,0,1,0]]}",
    );
    let err = parse(&path, frames, 10.0, Some(&no_scale))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("no_scale.json") && err.contains("scale"),
        "{err}"
    );
}
