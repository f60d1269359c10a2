//! `rslam eval recon`: mapping metrics of a mesh or point cloud against the ground-truth mesh.

use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

/// The unit square at height z as an ASCII PLY mesh, or its four corners and centre as a point
/// cloud.
fn square(z: f64, faces: bool) -> String {
    let mut corners = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    if !faces {
        corners.push([0.5, 0.5]);
    }
    let face_count = if faces { 2 } else { 0 };
    let mut text = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         element face {face_count}\nproperty list uchar int vertex_indices\nend_header\n",
        corners.len()
    );
    for [x, y] in corners {
        text += &format!("{x} {y} {z}\n");
    }
    if faces {
        text += "3 0 1 2\n3 0 2 3\n";
    }
    text
}

#[test]
fn prints_accuracy_completion_and_ratio_of_a_shifted_plane() {
    let ws = Workspace::new();
    ws.write("gt.ply", &square(0.0, true));
    ws.write("rec.ply", &square(0.03, true));
    let out = ws
        .rslam(&[
            "eval",
            "recon",
            "rec.ply",
            "--gt",
            "gt.ply",
            "--samples",
            "5000",
            "--cull",
            "none",
        ])
        .success();
    for fragment in [
        "reconstruction\trec.ply: mesh, 4 vertices, 2 triangles, 5000 points sampled on its surface",
        "accuracy (cm)\t3.0000",
        "completion (cm)\t3.0000",
        "completion ratio (< 5 cm, %)\t100.00",
    ] {
        assert!(out.contains(fragment), "missing '{fragment}' in:\n{out}");
    }
    let strict = ws
        .rslam(&[
            "eval",
            "recon",
            "rec.ply",
            "--gt",
            "gt.ply",
            "--samples",
            "5000",
            "--threshold-cm",
            "2",
            "--cull",
            "none",
        ])
        .success();
    assert!(
        strict.contains("completion ratio (< 2 cm, %)\t0.00"),
        "{strict}"
    );
}

#[test]
fn json_has_the_metrics_and_what_was_sampled() {
    let ws = Workspace::new();
    ws.write("gt.ply", &square(0.0, true));
    ws.write("cloud.ply", &square(0.01, false));
    let out = ws
        .rslam(&[
            "eval",
            "recon",
            "cloud.ply",
            "--gt",
            "gt.ply",
            "--samples",
            "3",
            "--seed",
            "9",
            "--cull",
            "none",
            "--json",
        ])
        .success();
    let json: serde_json::Value =
        serde_json::from_str(&out).unwrap_or_else(|e| panic!("{e}:\n{out}"));
    assert!(
        (json["accuracy_cm"].as_f64().unwrap() - 1.0).abs() < 1e-4,
        "{out}"
    );
    assert!(json["completion_cm"].as_f64().unwrap() > 1.0, "{out}");
    assert!(json["completion_ratio_percent"].is_number(), "{out}");
    assert_eq!(json["options"]["seed"], 9);
    assert_eq!(json["options"]["threshold_cm"], 5.0);
    assert_eq!(json["reconstruction"]["kind"], "point_cloud");
    assert_eq!(json["reconstruction"]["samples"], 3);
    assert_eq!(json["ground_truth"]["kind"], "mesh");
}

#[test]
fn bad_input_is_a_one_line_error_and_trajectories_still_evaluate() {
    let ws = Workspace::new();
    ws.write("gt.ply", &square(0.0, true));
    ws.write(
        "empty.ply",
        "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n",
    );
    let err = ws
        .rslam(&[
            "eval",
            "recon",
            "empty.ply",
            "--gt",
            "gt.ply",
            "--cull",
            "none",
        ])
        .fails_with(
            2,
            &["empty.ply: no vertices: expected a mesh or a point cloud"],
        );
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    ws.rslam(&["eval", "recon", "gt.ply"])
        .fails_with(2, &["--gt"]);
    ws.rslam(&[
        "eval",
        "recon",
        "gt.ply",
        "--gt",
        "gt.ply",
        "--samples",
        "0",
    ])
    .fails_with(2, &["samples = 0"]);
    let err = ws
        .rslam(&["eval", "recon", "gt.ply", "--gt", "gt.ply"])
        .fails_with(
            2,
            &["culling = visible: expected the ground-truth cameras of the dataset (--dataset DIR), or culling none"],
        );
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    ws.rslam(&[
        "eval",
        "recon",
        "gt.ply",
        "--gt",
        "gt.ply",
        "--dataset",
        "nowhere",
    ])
    .fails_with(2, &["nowhere"]);
    let help = ws.rslam(&["eval", "recon", "--help"]).success();
    assert!(
        help.contains("Distances are to the other side's surface"),
        "{help}"
    );
    assert!(ws.rslam(&["eval", "--help"]).success().contains("recon"));
    // A trajectory pair still goes to trajectory evaluation.
    let traj = "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n2 2 1 0 0 0 0 1\n";
    ws.write("traj.txt", traj);
    assert!(ws
        .rslam(&["eval", "traj.txt", "traj.txt"])
        .success()
        .contains("pairs\t3"));
}

/// The scene's mesh against itself over what 4 frames of a TUM dataset, a stereo rig and two
/// agents saw: perfect, with the culling, its views and what it kept reported.
#[test]
fn culls_to_the_views_of_a_dataset_a_rig_and_agents() {
    let ws = Workspace::new();
    ws.rslam(&["scene", "export", "room0", "--out", "room0.ply"])
        .success();
    let render = |out: &str, extra: &[&str]| {
        let mut args = vec!["render", "--scene", "room0", "--frames", "4", "--out", out];
        args.extend_from_slice(extra);
        ws.rslam(&args).success();
    };
    render("tum", &["--format", "tum", "--camera", SMALL_CAMERA]);
    render("rig", &["--rig", "stereo-imu", "--format", "euroc"]);
    render("agents", &["--agents", "2", "--camera", SMALL_CAMERA]);
    let frames_of = |camera: &str| {
        let csv = std::fs::read_to_string(ws.path(&format!("rig/mav0/{camera}/data.csv"))).unwrap();
        csv.lines().filter(|l| !l.starts_with('#')).count()
    };
    let rig_views = frames_of("cam0") + frames_of("cam1");
    assert!(rig_views >= 4, "{rig_views}");
    let recon = |dataset: &str, extra: &[&str]| {
        let mut args = vec![
            "eval",
            "recon",
            "room0.ply",
            "--gt",
            "room0.ply",
            "--dataset",
            dataset,
            "--samples",
            "20000",
        ];
        args.extend_from_slice(extra);
        ws.rslam(&args).success()
    };
    for (dataset, views) in [("tum", 4), ("rig", rig_views), ("agents", 8)] {
        let out = recon(dataset, &[]);
        for fragment in [
            format!("culling\tvisible: points a ground-truth camera saw past the ground-truth mesh (2 cm tolerance), {views} views; kept "),
            "accuracy (cm)\t0.0000".into(),
            "completion (cm)\t0.0000".into(),
            "completion ratio (< 5 cm, %)\t100.00".into(),
        ] {
            assert!(out.contains(&fragment), "{dataset}: missing '{fragment}' in:\n{out}");
        }
        let json: serde_json::Value =
            serde_json::from_str(&recon(dataset, &["--cull", "frustum", "--json"])).unwrap();
        let kept = json["ground_truth"]["kept"].as_u64().unwrap();
        assert!(
            kept > 100 && kept < 19_000,
            "{dataset}: a few frames see part of the room: {json}"
        );
        assert_eq!(json["options"]["culling"], "frustum");
        assert_eq!(json["views"], views);
    }
}
