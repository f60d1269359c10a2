//! `rslam render --scene capture.ply`: a Gaussian-splat capture made by the test (a box room of
//! flat Gaussians), rendered along a path file into a dataset, its scale and depth settings in
//! the manifest, and the items it refuses.

use glam::{DQuat, DVec3};
use rslam_core::dataset::decode_depth_png;
use rslam_core::splat_io::{write_splat_ply, SplatCloud};

use crate::dataset_check::{files, manifest};
use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

/// A 4 × 3 × 2.5 m room (x, y, z; z up) of flat Gaussians 4 cm apart on its walls, each wall in
/// 0.5 m squares of two colours, as a capture in metres.
fn room_capture() -> SplatCloud {
    const SPACING: f32 = 0.04;
    let (min, max) = ([-2.0f32, -1.5, 0.0], [2.0f32, 1.5, 2.5]);
    let mut cloud = SplatCloud::default();
    for axis in 0..3 {
        let [a, b] = [[1, 2], [0, 2], [0, 1]][axis];
        for at in [min[axis], max[axis]] {
            let count = |k: usize| ((max[k] - min[k]) / SPACING).round() as usize;
            for i in 0..count(a) {
                for j in 0..count(b) {
                    let mut mean = [0.0; 3];
                    mean[axis] = at;
                    mean[a] = min[a] + SPACING * (i as f32 + 0.5);
                    mean[b] = min[b] + SPACING * (j as f32 + 0.5);
                    let square =
                        ((mean[a] - min[a]) / 0.5) as usize + ((mean[b] - min[b]) / 0.5) as usize;
                    let grey = if square.is_multiple_of(2) { 0.25 } else { 0.75 };
                    let mut scale = [0.03f32.ln(); 3];
                    scale[axis] = 0.002f32.ln();
                    cloud.means.push(mean);
                    cloud.log_scales.push(scale);
                    cloud.rotations.push([1.0, 0.0, 0.0, 0.0]);
                    cloud.opacity_logits.push(4.0);
                    cloud.sh.push([(grey - 0.5) / 0.282_094_8; 3]);
                }
            }
        }
    }
    cloud
}

/// 6 camera-to-world poses from the room's middle, turning about the vertical, every length
/// times `scale`: OpenCV camera axes, looking along world +x with z up, turned by yaw about z.
fn poses(scale: f64) -> Vec<(DQuat, DVec3)> {
    let look_x = DQuat::from_mat3(&glam::DMat3::from_cols(
        DVec3::new(0.0, -1.0, 0.0),
        DVec3::new(0.0, 0.0, -1.0),
        DVec3::new(1.0, 0.0, 0.0),
    ));
    (0..6)
        .map(|i| {
            let rotation = DQuat::from_rotation_z(0.2 * i as f64) * look_x;
            (rotation, scale * DVec3::new(-0.5, 0.1 * i as f64, 1.2))
        })
        .collect()
}

fn tum_path(scale: f64) -> String {
    (poses(scale).iter().enumerate())
        .map(|(i, (q, p))| {
            let t = i as f64 / 30.0;
            format!(
                "{t:.6} {} {} {} {} {} {} {}\n",
                p.x, p.y, p.z, q.x, q.y, q.z, q.w
            )
        })
        .collect()
}

/// The same poses as COLMAP writes them: world-to-camera, a line of (no) points after each.
fn colmap_images(scale: f64) -> String {
    let mut text = "# Image list with two lines of data per image:\n".to_string();
    for (i, (q, p)) in poses(scale).iter().enumerate() {
        let (r, t) = (q.inverse(), -(q.inverse() * *p));
        text += &format!(
            "{} {} {} {} {} {} {} {} 1 frame{i:04}.jpg\n\n",
            i + 1,
            r.w,
            r.x,
            r.y,
            r.z,
            t.x,
            t.y,
            t.z
        );
    }
    text
}

/// Row-major camera-to-world numbers with OpenGL camera axes (nerfstudio's) of an OpenCV pose.
fn opengl_rows(rotation: DQuat, position: DVec3) -> Vec<f64> {
    let r =
        glam::DMat3::from_quat(rotation) * glam::DMat3::from_diagonal(DVec3::new(1.0, -1.0, -1.0));
    let c = r.to_cols_array_2d();
    (0..3)
        .flat_map(|row| [c[0][row], c[1][row], c[2][row], position[row]])
        .chain([0.0, 0.0, 0.0, 1.0])
        .collect()
}

/// The path as nerfstudio's viewer writes a camera path, in the capture's frame.
fn camera_path_json() -> String {
    let cameras: Vec<String> = (poses(1.0).iter())
        .map(|(q, p)| {
            format!(
                "{{\"camera_to_world\": {:?}, \"fov\": 70}}",
                opengl_rows(*q, *p)
            )
        })
        .collect();
    format!("{{\"fps\": 30, \"camera_path\": [{}]}}", cameras.join(", "))
}

/// The path as a nerfstudio `transforms.json` in an original frame, and the
/// `dataparser_transforms.json` (a quarter turn about z, a shift, a scale of 2) that moves it
/// into the capture's frame.
fn transforms_json() -> (String, String) {
    let turn = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
    let (shift, scale) = (DVec3::new(1.0, 2.0, 3.0), 2.0);
    let frames: Vec<String> = (poses(1.0).iter().enumerate())
        .map(|(i, (q, p))| {
            let original = (turn.inverse() * *q, turn.inverse() * (*p / scale - shift));
            let rows = opengl_rows(original.0, original.1);
            let matrix: Vec<&[f64]> = rows.chunks(4).collect();
            format!(
                "{{\"file_path\": \"images/frame_{i:05}.png\", \"transform_matrix\": {matrix:?}}}"
            )
        })
        .collect();
    let m = glam::DMat3::from_quat(turn).to_cols_array_2d();
    let transform: Vec<[f64; 4]> = (0..3)
        .map(|r| [m[0][r], m[1][r], m[2][r], shift[r]])
        .collect();
    (
        format!("{{\"frames\": [{}]}}", frames.join(", ")),
        format!("{{\"transform\": {transform:?}, \"scale\": {scale}}}"),
    )
}

fn capture_workspace() -> Workspace {
    let ws = Workspace::new();
    std::fs::write(ws.path("room.ply"), write_splat_ply(&room_capture())).unwrap();
    std::fs::write(
        ws.path("half.ply"),
        write_splat_ply(&room_capture().scaled(0.5)),
    )
    .unwrap();
    ws.write("path.txt", &tum_path(1.0));
    ws.write("half_path.txt", &tum_path(0.5));
    ws.write("images.txt", &colmap_images(1.0));
    ws.write("camera_path.json", &camera_path_json());
    let (transforms, dataparser) = transforms_json();
    ws.write("transforms.json", &transforms);
    ws.write("dataparser_transforms.json", &dataparser);
    ws
}

fn render(
    ws: &Workspace,
    out: &str,
    scene: &str,
    traj: &str,
    extra: &[&str],
) -> crate::harness::Run {
    let args = [
        &[
            "render",
            "--scene",
            scene,
            "--traj",
            traj,
            "--format",
            "tum",
            "--camera",
            SMALL_CAMERA,
            "--out",
            out,
        ][..],
        extra,
    ]
    .concat();
    ws.rslam(&args)
}

fn depths(ws: &Workspace, out: &str) -> Vec<Vec<f32>> {
    files(&ws.path(out).join("depth"), "")
        .iter()
        .map(|p| decode_depth_png(p, 5000.0).unwrap().data)
        .collect()
}

#[test]
fn a_capture_renders_along_a_path_into_a_tum_dataset() {
    let ws = capture_workspace();
    render(&ws, "clean", "room.ply", "path.txt", &[]).success();
    render(&ws, "fog", "room.ply", "path.txt", &["--perturb", "fog:3"]).success();
    let m = manifest(&ws.path("fog"));
    assert_eq!(m.frame_count, 6);
    assert!(m.source.ends_with("room.ply"));
    let capture = &m.extra["capture"];
    assert_eq!(capture["depth"], "expected");
    assert_eq!(capture["min_opacity"], 0.5);
    assert!(capture["metres_per_unit"].is_null(), "{capture}");
    // The camera stands inside a closed room: every pixel sees a wall, 0.5 to 4.5 m away.
    for frame in depths(&ws, "fog") {
        assert!(
            frame.iter().all(|&z| (0.5..4.5).contains(&z)),
            "depth outside the room"
        );
    }
    let clean = files(&ws.path("clean").join("rgb"), "");
    let fog = files(&ws.path("fog").join("rgb"), "");
    assert_eq!(clean.len(), 6);
    assert_ne!(
        std::fs::read(&clean[0]).unwrap(),
        std::fs::read(&fog[0]).unwrap()
    );
}

#[test]
fn the_capture_scale_scales_depth_and_is_recorded() {
    let ws = capture_workspace();
    // The room at half size, seen from the path at half size: every depth halves.
    render(
        &ws,
        "metres",
        "room.ply",
        "path.txt",
        &["--capture-scale", "1"],
    )
    .success();
    render(
        &ws,
        "half",
        "half.ply",
        "half_path.txt",
        &["--capture-scale", "1"],
    )
    .success();
    render(
        &ws,
        "stated",
        "room.ply",
        "half_path.txt",
        &["--capture-scale", "0.5"],
    )
    .success();
    assert_eq!(
        manifest(&ws.path("stated")).extra["capture"]["metres_per_unit"],
        0.5
    );
    // The capture's own COLMAP path is in its units and is scaled with it.
    render(
        &ws,
        "colmap",
        "room.ply",
        "images.txt",
        &["--capture-scale", "0.5"],
    )
    .success();
    let metres = depths(&ws, "metres");
    for out in ["half", "stated", "colmap"] {
        for (full, half) in metres.iter().zip(depths(&ws, out)) {
            let worst = full
                .iter()
                .zip(&half)
                .map(|(f, h)| (0.5 * f - h).abs())
                .fold(0.0f32, f32::max);
            // Two steps of the TUM depth PNG (0.2 mm).
            assert!(worst <= 0.0004, "{out}: depth off half by {worst} m");
        }
    }
    render(
        &ws,
        "median",
        "room.ply",
        "path.txt",
        &["--capture-depth", "median", "--capture-min-opacity", "0.9"],
    )
    .success();
    let capture = &manifest(&ws.path("median")).extra["capture"];
    assert_eq!(
        (capture["depth"].as_str(), capture["min_opacity"].as_f64()),
        (Some("median"), Some(0.9f32 as f64))
    );
}

#[test]
fn a_capture_refuses_items_in_metres_without_a_scale_and_light_items() {
    let ws = capture_workspace();
    render(
        &ws,
        "a",
        "room.ply",
        "path.txt",
        &["--perturb", "depth_noise:2"],
    )
    .fails_with(2, &["--capture-scale", "room.ply", "depth_noise", "metres"]);
    render(
        &ws,
        "b",
        "room.ply",
        "path.txt",
        &["--perturb", "trans:0.01"],
    )
    .fails_with(2, &["--capture-scale", "'trans'"]);
    render(
        &ws,
        "c",
        "room.ply",
        "path.txt",
        &["--perturb", "depth_noise:2", "--capture-scale", "1"],
    )
    .success();
    render(
        &ws,
        "d",
        "room.ply",
        "path.txt",
        &["--perturb", "lights:1/0.4/0.3"],
    )
    .fails_with(2, &["Gaussian-splat capture", "light"]);
    render(&ws, "e", "room.ply", "path.txt", &["--capture-scale=-1"])
        .fails_with(2, &["room.ply", "-1", "positive"]);
    render(
        &ws,
        "f",
        "room.ply",
        "path.txt",
        &["--capture-min-opacity", "1.5"],
    )
    .fails_with(2, &["--capture-min-opacity", "1.5"]);
    ws.rslam(&["scene", "export", "room.ply", "--out", "mesh.ply"])
        .fails_with(
            2,
            &["room.ply", "Gaussian-splat capture", "no triangle mesh"],
        );
    assert!(
        !ws.path("a").exists() && !ws.path("d").exists(),
        "nothing written for a refused job"
    );
}

#[test]
fn a_bad_capture_is_refused_naming_the_file_and_property() {
    let ws = capture_workspace();
    let bytes = write_splat_ply(&room_capture());
    let text = String::from_utf8_lossy(&bytes[..400]).to_string();
    let header_end = text.find("end_header\n").unwrap() + "end_header\n".len();
    let header =
        text[..header_end].replace("property float scale_1\n", "property float scale_one\n");
    let mut renamed = header.into_bytes();
    renamed.extend(&bytes[header_end..]);
    std::fs::write(ws.path("renamed.ply"), renamed).unwrap();
    render(&ws, "out", "renamed.ply", "path.txt", &[]).fails_with(2, &["renamed.ply", "'scale_1'"]);
}

#[test]
fn nerfstudio_paths_render_the_views_of_the_same_poses() {
    let ws = capture_workspace();
    render(&ws, "tum", "room.ply", "path.txt", &[]).success();
    render(&ws, "camera_path", "room.ply", "camera_path.json", &[]).success();
    render(
        &ws,
        "transforms",
        "room.ply",
        "transforms.json",
        &["--dataparser-transforms", "dataparser_transforms.json"],
    )
    .success();
    let tum = depths(&ws, "tum");
    for out in ["camera_path", "transforms"] {
        for (a, b) in tum.iter().zip(depths(&ws, out)) {
            let worst = a
                .iter()
                .zip(&b)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0f32, f32::max);
            assert!(worst <= 0.0004, "{out}: depth off by {worst} m");
        }
    }
    // Without the dataparser's move, the transforms.json cameras stand elsewhere.
    render(&ws, "unmoved", "room.ply", "transforms.json", &[]).success();
    assert_ne!(depths(&ws, "unmoved")[0], tum[0]);
    render(
        &ws,
        "wrong",
        "room.ply",
        "path.txt",
        &["--dataparser-transforms", "dataparser_transforms.json"],
    )
    .fails_with(2, &["path.txt", "dataparser"]);
}

#[test]
fn a_capture_of_a_built_in_scene_renders_along_its_path() {
    let ws = capture_workspace();
    ws.rslam(&[
        "scene",
        "export",
        "room0",
        "--gaussians",
        "20000",
        "--out",
        "room0.ply",
    ])
    .success();
    ws.rslam(&["scene", "traj", "room0", "--out", "room0.txt"])
        .success();
    render(&ws, "splats", "room0.ply", "room0.txt", &["--frames", "2"]).success();
    let m = manifest(&ws.path("splats"));
    assert_eq!(m.frame_count, 2);
    // room0's walls enclose its path: every pixel sees a Gaussian.
    for frame in depths(&ws, "splats") {
        assert!(
            frame.iter().all(|&z| z > 0.1 && z < 10.0),
            "a pixel without depth"
        );
    }
    ws.rslam(&[
        "scene",
        "export",
        "room0.ply",
        "--gaussians",
        "10",
        "--out",
        "again.ply",
    ])
    .fails_with(2, &["room0.ply", "capture already"]);
}

#[test]
fn a_capture_goes_through_the_shutter_the_lens_and_the_frame_plan() {
    let ws = capture_workspace();
    render(&ws, "clean", "room.ply", "path.txt", &[]).success();
    let colour = |out: &str, i: usize| {
        let frames = files(&ws.path(out).join("rgb"), "");
        std::fs::read(&frames[i]).unwrap()
    };
    // Under a shutter every sub-render draws the capture again (rolling_shutter takes the same
    // path), under a lens the wider view is drawn and resampled; depth stays inside the room.
    for (out, spec) in [
        ("blurred", "exposure:30"),
        ("lens", "distortion:radtan(-0.28,0.07,0.0002,0.00002)"),
        ("plan", "fast:2,rot:1"),
    ] {
        // Few frames: each sub-render of a capture reads its copy count back, slow on lavapipe.
        let args = ["--perturb", spec, "--frames", "4"];
        render(&ws, out, "room.ply", "path.txt", &args).success();
        let frames = depths(&ws, out);
        let seen: usize = (frames.iter())
            .map(|f| f.iter().filter(|&&z| z > 0.0).count())
            .sum();
        let inside = (frames.iter().flatten()).all(|&z| z == 0.0 || (0.3..4.5).contains(&z));
        assert!(
            inside && seen > frames.len() * frames[0].len() / 2,
            "{spec}: depth"
        );
        assert!(
            colour(out, 1) != colour("clean", 1),
            "{spec}: colour unchanged"
        );
    }
    assert_eq!(
        depths(&ws, "plan").len(),
        2,
        "fast:2 keeps every other frame"
    );
}
