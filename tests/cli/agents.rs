//! `rslam render --agents N`: a folder of agents, each a dataset on a path of its own in one world
//! frame, that `rslam eval --agents` reads.

use crate::dataset_check::*;
use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

/// `rslam render` of 4 noisy frames of room0 into `out`, with `extra` arguments.
fn render_room0(ws: &Workspace, out: &str, extra: &[&str]) {
    let mut args = vec![
        "render",
        "--scene",
        "room0",
        "--frames",
        "4",
        "--camera",
        SMALL_CAMERA,
        "--perturb",
        "gaussian_noise:3",
        "--out",
        out,
    ];
    args.extend_from_slice(extra);
    ws.rslam(&args).success();
}

#[test]
fn agents_are_datasets_on_their_own_paths_and_agent0_is_the_plain_render() {
    let ws = Workspace::new();
    render_room0(&ws, "agents", &["--agents", "3"]);
    render_room0(&ws, "single", &[]);
    let agent = |k: usize| ws.path(&format!("agents/agent{k}"));
    assert_same_tree(&agent(0).join("results"), &ws.path("single/results"));
    assert_eq!(
        replica_trajectory(&agent(0)),
        replica_trajectory(&ws.path("single"))
    );

    let paths: Vec<_> = (0..3).map(|k| replica_trajectory(&agent(k))).collect();
    for (k, path) in paths.iter().enumerate() {
        let expected = rslam_render::agent_trajectory("room0", k).unwrap();
        assert_poses_close(&path.poses, &expected.poses[..4], 1e-6);
        let manifest = manifest(&agent(k));
        assert_eq!(manifest.seed, k as u64);
        assert_eq!(manifest.extra["agent"], k);
    }
    assert!(
        (paths[1].poses[0].translation - paths[2].poses[0].translation).length() > 0.3,
        "agents 1 and 2 start at the same place"
    );
    assert_ne!(
        tree(&agent(1).join("results")),
        tree(&agent(2).join("results"))
    );

    // A multi-agent estimate that is each agent's ground truth: joint ATE 0 in one world frame.
    for k in 0..3 {
        std::fs::copy(agent(k).join("traj.txt"), agent(k).join("estimate.txt")).unwrap();
    }
    let json = ws
        .rslam(&["eval", "--agents", "agents", "--json"])
        .success();
    let value: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(value["agents"].as_array().unwrap().len(), 3);
    assert!(
        value["joint"]["ate"]["rmse"].as_f64().unwrap() < 1e-6,
        "{json}"
    );

    // The same command again finds every agent complete.
    render_room0(&ws, "agents", &["--agents", "3"]);
}

#[test]
fn bad_agent_requests_are_one_line_errors() {
    let ws = Workspace::new();
    ws.rslam(&["render", "--scene", "room0", "--agents", "0", "--out", "a"])
        .fails_with(2, &["--agents: 0: expected at least one agent"]);
    ws.write("mesh.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    ws.rslam(&[
        "render", "--scene", "mesh.ply", "--agents", "2", "--out", "b",
    ])
    .fails_with(2, &["--agents: scene 'mesh.ply' is not a built-in one"]);
    ws.rslam(&[
        "render", "--scene", "room0", "--agents", "2", "--traj", "t.txt", "--out", "c",
    ])
    .fails_with(2, &["--traj"]);
    ws.write("d/notes.txt", "mine");
    ws.rslam(&["render", "--scene", "room0", "--agents", "2", "--out", "d"])
        .fails_with(2, &["'notes.txt', which is no agent folder"]);
    assert!(!ws.path("b").exists() && !ws.path("d/agent0").exists());
}
