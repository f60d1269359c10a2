//! `rslam render`: both layouts read back, bad input, interruption.

use std::time::Duration;

use rslam_core::Intrinsics;
use rslam_render::load_scene;
use rslam_render::raster::depth_agreement;
use rslam_render::raycast::RayCaster;

use crate::dataset_check::*;
use crate::harness::{sorted_names, Workspace};

/// A small camera keeps the tests fast; the field of view is the Replica camera's.
pub const SMALL_CAMERA: &str = "120,68,60,60,59.5,33.5";

fn small_camera() -> Intrinsics {
    Intrinsics::parse(SMALL_CAMERA).unwrap()
}

/// One 16-bit step of the layout's depth scale, plus the oracle's own relative tolerance.
fn assert_depth_matches_oracle(depth: &rslam_core::DepthImage, pose: &rslam_core::Pose, step: f32) {
    let scene = load_scene("room0").unwrap();
    let oracle = RayCaster::new(&scene).depth_image(pose, &small_camera());
    let quantised = rslam_core::DepthImage {
        data: oracle
            .data
            .iter()
            .map(|z| (z * (1.0 / step)).round() * step)
            .collect(),
        ..oracle
    };
    let a = depth_agreement(depth, &quantised);
    assert!(a.compared > depth.data.len() / 2, "{a:?}");
    assert_eq!(a.mask_mismatches, 0, "{a:?}");
    assert!(a.max_relative_error < 1e-3, "{a:?}");
}

#[test]
fn replica_layout_reads_back() {
    let ws = Workspace::new();
    ws.rslam(&[
        "render",
        "--scene",
        "room0",
        "--frames",
        "5",
        "--camera",
        SMALL_CAMERA,
        "--out",
        "ds",
    ])
    .success();
    let root = ws.path("ds");
    assert_eq!(files(&root.join("results"), "frame").len(), 5);
    assert_eq!(files(&root.join("results"), "depth").len(), 5);
    let rgb = replica_rgb(&root, 4);
    assert_eq!((rgb.width, rgb.height), (120, 68));
    let gt = replica_trajectory(&root);
    let scene = load_scene("room0").unwrap();
    let clean = &scene.default_trajectory.as_ref().unwrap().poses[..5];
    assert_poses_close(&gt.poses, clean, 1e-9);
    assert_depth_matches_oracle(&replica_depth(&root, 3), &clean[3], 1.0 / 6553.5);
    let cam: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root.join("cam_params.json")).unwrap())
            .unwrap();
    assert_eq!(cam["camera"]["w"], 120);
    assert_eq!(cam["camera"]["scale"], 6553.5);
    let m = manifest(&root);
    assert_eq!(m.frame_count, 5);
    assert_eq!(m.source, "room0");
}

#[test]
fn tum_layout_reads_back() {
    let ws = Workspace::new();
    ws.rslam(&[
        "render",
        "--scene",
        "room0",
        "--frames",
        "4",
        "--camera",
        SMALL_CAMERA,
        "--format",
        "tum",
        "--rate",
        "30",
        "--out",
        "ds",
    ])
    .success();
    let root = ws.path("ds");
    let rgb_lines = lines(&root.join("rgb.txt"));
    assert_eq!(
        rgb_lines,
        [
            "0.000000 rgb/0.000000.png",
            "0.033333 rgb/0.033333.png",
            "0.066667 rgb/0.066667.png",
            "0.100000 rgb/0.100000.png"
        ]
    );
    let raw_rgb_txt = std::fs::read_to_string(root.join("rgb.txt")).unwrap();
    assert_eq!(
        raw_rgb_txt
            .lines()
            .take_while(|l| l.starts_with('#'))
            .count(),
        3
    );
    let assoc = std::fs::read_to_string(root.join("associations.txt")).unwrap();
    assert_eq!(
        assoc.lines().next(),
        Some("0.000000 rgb/0.000000.png 0.000000 depth/0.000000.png")
    );
    assert!(!assoc.contains('#'), "ORB-SLAM3 reads associations raw");
    let gt = tum_trajectory(&root);
    let clean = &load_scene("room0")
        .unwrap()
        .default_trajectory
        .unwrap()
        .poses[..4];
    assert_poses_close(&gt.poses, clean, 1e-5);
    let depth =
        rslam_core::dataset::decode_depth_png(&root.join("depth/0.066667.png"), 5000.0).unwrap();
    assert_depth_matches_oracle(&depth, &clean[2], 1.0 / 5000.0);
    let yaml = std::fs::read_to_string(root.join("orbslam3.yaml")).unwrap();
    for key in [
        "RGBD.DepthMapFactor: 5000.0",
        "Camera1.fx: 60.000000",
        "Camera.width: 120",
        "Viewer.ViewpointF",
    ] {
        assert!(yaml.contains(key), "orbslam3.yaml lacks {key}");
    }
    assert!(ws.path("ds/rslam.json").exists());
}

#[test]
fn a_ros2_bag_is_sealed_like_a_dataset_and_perturbed_into_a_sealed_bag_of_its_own() {
    let ws = Workspace::new();
    let render = |out: &str, extra: &[&str]| {
        let mut args = vec![
            "render",
            "--scene",
            "room0",
            "--frames",
            "3",
            "--camera",
            SMALL_CAMERA,
            "--format",
            "ros2",
            "--out",
            out,
        ];
        args.extend_from_slice(extra);
        ws.rslam(&args)
    };
    render("bag", &[]).success();
    assert_eq!(
        sorted_names(&ws.path("bag")),
        ["bag_0.mcap", "metadata.yaml", "rslam.b3sum", "rslam.json"]
    );
    ws.rslam(&["verify", "bag"]).success();
    let again = render("bag", &[]);
    again.success();
    assert!(
        again.stderr().contains("already complete"),
        "{}",
        again.stderr()
    );
    let perturb = |out: &str| {
        ws.rslam(&[
            "perturb",
            "--input",
            "bag",
            "--perturb",
            "fog:3",
            "--out",
            out,
        ])
    };
    perturb("p").success();
    assert_eq!(
        sorted_names(&ws.path("p")),
        ["metadata.yaml", "p_0.mcap", "rslam.b3sum", "rslam.json"]
    );
    ws.rslam(&["verify", "p"]).success();
    perturb("bag").fails_with(2, &["bag", "is the input itself"]);
}

#[test]
fn trajectory_file_drives_the_camera() {
    let ws = Workspace::new();
    ws.rslam(&["scene", "traj", "room0", "--out", "traj.txt"])
        .success();
    let all = std::fs::read_to_string(ws.path("traj.txt")).unwrap();
    let lines: Vec<&str> = all.lines().skip(100).take(3).collect();
    ws.write("three.txt", &(lines.join("\n") + "\n"));
    ws.rslam(&[
        "render",
        "--scene",
        "room0",
        "--traj",
        "three.txt",
        "--camera",
        SMALL_CAMERA,
        "--out",
        "ds",
    ])
    .success();
    let gt = replica_trajectory(&ws.path("ds"));
    let clean = &load_scene("room0")
        .unwrap()
        .default_trajectory
        .unwrap()
        .poses[100..103];
    assert_poses_close(&gt.poses, clean, 1e-9);
}

#[test]
fn bad_input_is_a_one_line_error() {
    let ws = Workspace::new();
    let run = |args: &[&str]| {
        ws.rslam(
            &[
                &["render", "--out", "ds", "--camera", SMALL_CAMERA][..],
                args,
            ]
            .concat(),
        )
    };
    run(&["--scene", "nowhere.ply"]).fails_with(2, &["nowhere.ply"]);
    run(&["--scene", "kitchen9"]).fails_with(2, &["kitchen9", "room0", "office4"]);
    ws.write("mesh.stl", "solid x\n");
    run(&["--scene", "mesh.stl"]).fails_with(2, &["mesh.stl", ".ply"]);
    ws.write("truncated.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\x00\x00");
    run(&["--scene", "truncated.ply"]).fails_with(2, &["truncated.ply"]);
    run(&["--scene", "room0", "--traj", "missing.txt"]).fails_with(2, &["missing.txt"]);
    ws.write("bad.txt", "0 0 0 0 0 0 0 1\n0.1 0 0 zero 0 0 0 1\n");
    run(&["--scene", "room0", "--traj", "bad.txt"]).fails_with(2, &["bad.txt:2"]);
    run(&["--scene", "room0", "--frames", "999999"]).fails_with(2, &["--frames"]);
    ws.rslam(&[
        "render", "--scene", "room0", "--out", "ds", "--camera", "10,10",
    ])
    .fails_with(2, &["camera"]);
    run(&["--scene", "room0", "--perturb", "gausian_noise:3"])
        .fails_with(2, &["gausian_noise", "gaussian_noise"]);
    run(&["--scene", "room0", "--perturb", "brightness:9"]).fails_with(2, &["brightness:9"]);
    assert!(!ws.path("ds/rslam.json").exists());
}

#[test]
fn interrupted_render_leaves_no_manifest() {
    let ws = Workspace::new();
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_rslam"))
        .args([
            "render",
            "--scene",
            "room0",
            "--camera",
            SMALL_CAMERA,
            "--out",
        ])
        .arg(ws.path("ds"))
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Wait until frames are being written, then interrupt.
    let results = ws.path("ds/results");
    for _ in 0..600 {
        if results.exists() && files(&results, "frame").len() > 3 {
            break;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    let status = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    assert_eq!(
        out.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("interrupted"));
    assert!(!ws.path("ds/rslam.json").exists());
}
