//! People walking through a scene end to end: `actors` in the TUM layout (the walkers' poses in
//! the manifest, depth only ever nearer where they pass), and the refusals naming the item: a mesh file (no free floor), a recorded dataset (no scene), a bad value, a room too
//! crowded for the walkers asked for.

use rslam_core::dataset::decode_depth_png;

use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

fn manifest(ws: &Workspace, out: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(ws.path(&format!("{out}/rslam.json"))).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn render_office1(ws: &Workspace, out: &str, spec: Option<&str>) {
    let mut args = vec![
        "render", "--scene", "office1", "--format", "tum", "--out", out,
    ];
    args.extend(["--camera", SMALL_CAMERA, "--frames", "160", "--seed", "3"]);
    args.extend(spec.iter().flat_map(|s| ["--perturb", s]));
    ws.rslam(&args).success();
}

#[test]
fn walkers_cross_the_view_of_a_tum_dataset_and_leave_the_other_frames_alone() {
    let ws = Workspace::new();
    render_office1(&ws, "clean", None);
    render_office1(&ws, "walkers", Some("actors:4"));
    let actors = &manifest(&ws, "walkers")["extra"]["actors"];
    let walkers = actors["walkers"].as_array().unwrap();
    assert_eq!(walkers.len(), 2, "actors:4 is two walkers");
    for w in walkers {
        let height = w["height_m"].as_f64().unwrap();
        assert!((1.55..=1.9).contains(&height), "{w}");
        assert_eq!(w["speed_m_s"].as_f64(), Some(1.2));
    }
    let frames = actors["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 160);
    // Walkers move at most their speed between frames (20 Hz).
    for pair in frames.windows(2) {
        for (a, b) in pair[0]
            .as_array()
            .unwrap()
            .iter()
            .zip(pair[1].as_array().unwrap())
        {
            let d = ((a[0].as_f64().unwrap() - b[0].as_f64().unwrap()).powi(2)
                + (a[1].as_f64().unwrap() - b[1].as_f64().unwrap()).powi(2))
            .sqrt();
            assert!(d <= 1.5 * 1.2 / 20.0 + 1e-3, "a walker jumped {d} m");
        }
    }
    // A walker only hides the room: where depth changed it came nearer, and the walkers
    // cover part of a frame, more as they pass close.
    let depth_files = crate::harness::sorted_names(&ws.path("clean/depth"));
    assert_eq!(depth_files.len(), 160);
    let mut covered = Vec::new();
    for name in &depth_files {
        let read = |out: &str| {
            decode_depth_png(&ws.path(&format!("{out}/depth/{name}")), 5000.0).expect("depth png")
        };
        let (clean, walkers) = (read("clean"), read("walkers"));
        let mut changed = 0;
        for (c, w) in clean.data.iter().zip(&walkers.data) {
            if c != w {
                changed += 1;
                assert!(
                    *c == 0.0 || w < c,
                    "{name}: depth moved away from the camera"
                );
            }
        }
        covered.push(changed as f64 / clean.data.len() as f64);
    }
    let most = covered.iter().copied().fold(0.0, f64::max);
    assert!(
        most > 0.1 && most < 0.9,
        "walkers cover at most {most} of a frame"
    );
    assert!(
        covered.iter().any(|&c| c < most / 4.0),
        "the walkers' share varies"
    );
}

#[test]
fn actors_are_refused_without_a_free_floor_a_scene_or_room_and_for_bad_values() {
    let ws = Workspace::new();
    ws.write("mesh.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    ws.write("path.txt", "0 0 0 0.5 0 0 0 1\n0.1 0 0 0.5 0 0 0 1\n");
    let mesh = [
        "render", "--scene", "mesh.ply", "--traj", "path.txt", "--out", "out",
    ];
    ws.rslam(&[&mesh[..], &["--perturb", "actors:2"]].concat())
        .fails_with(2, &["actors:2", "free floor", "'mesh.ply' is a mesh file"]);
    assert!(!ws.path("out").exists());
    let args = ["--camera", SMALL_CAMERA, "--frames", "4"];
    ws.render_room0("data", &args, None);
    ws.rslam(&[
        "perturb",
        "--input",
        "data",
        "--out",
        "p",
        "--perturb",
        "actors:1",
    ])
    .fails_with(2, &["actors:1", "needs a scene"]);
    ws.rslam(&[
        "render",
        "--scene",
        "room0",
        "--out",
        "bad",
        "--perturb",
        "actors:9/1/1",
    ])
    .fails_with(2, &["actors:9/1/1", "COUNT/SPEED/NEAR"]);
    let crowded = [
        "render", "--scene", "room1", "--out", "crowded", "--frames", "100",
    ];
    ws.rslam(&[&crowded[..], &["--perturb", "actors:8/1.4/0.4"]].concat())
        .fails_with(
            2,
            &["room1", "no path over the free floor", "fewer walkers"],
        );
    assert!(!ws.path("crowded").exists());
}

#[test]
fn both_cameras_of_a_stereo_rig_see_the_same_walkers() {
    let ws = Workspace::new();
    let render = |out: &str, spec: Option<&str>| {
        let mut args = vec!["render", "--scene", "office0", "--rig", "stereo-imu"];
        args.extend([
            "--format", "euroc", "--frames", "60", "--seed", "2", "--out", out,
        ]);
        args.extend(spec.iter().flat_map(|s| ["--perturb", s]));
        ws.rslam(&args).success();
    };
    render("clean", None);
    render("walkers", Some("actors:5"));
    let changed = |camera: &str| -> Vec<bool> {
        let folder = format!("mav0/{camera}/data");
        let names = crate::harness::sorted_names(&ws.path(&format!("clean/{folder}")));
        (names.iter())
            .map(|name| {
                let read =
                    |out: &str| std::fs::read(ws.path(&format!("{out}/{folder}/{name}"))).unwrap();
                read("clean") != read("walkers")
            })
            .collect()
    };
    let (left, right) = (changed("cam0"), changed("cam1"));
    let frames = manifest(&ws, "walkers")["extra"]["actors"]["frames"].clone();
    assert_eq!(
        frames.as_array().unwrap().len(),
        left.len(),
        "a pose per cam0 frame"
    );
    let both = left.iter().zip(&right).filter(|(l, r)| **l && **r).count();
    let either = left.iter().zip(&right).filter(|(l, r)| **l || **r).count();
    assert!(either >= 5, "walkers seen in {either} of 60 frames");
    // 11 cm apart, the cameras see nearly the same: a walker at the edge of one view only.
    assert!(
        both as f64 >= 0.8 * either as f64,
        "{both} of {either} frames in both views"
    );
}
