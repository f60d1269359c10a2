//! `rslam eval --agent EST GT ...` and `--agents DIR`: several agents in one world frame.

use crate::eval::{identity, json_of, rigid, tum};
use crate::harness::Workspace;

/// Agent b's ground truth: another path than a's, in the same world frame.
fn other_path(p: [f64; 3]) -> [f64; 3] {
    [0.5 * p[0] + 1.0, 0.8 * p[1] - 0.5, p[2] + 0.3]
}

/// `a.txt`, `a_gt.txt`: agent a, exact up to a rigid motion common to both agents; `b.txt`,
/// `b_gt.txt`: agent b on another path, with the same motion and also shifted 0.5 m along x.
fn write_two_agents(ws: &Workspace) {
    ws.write("a.txt", &tum(150, 0.0, rigid));
    ws.write("a_gt.txt", &tum(150, 0.0, identity));
    let shifted = |p| {
        let [x, y, z] = rigid(other_path(p));
        [x + 0.5, y, z]
    };
    ws.write("b.txt", &tum(120, 0.0, shifted));
    ws.write("b_gt.txt", &tum(120, 0.0, other_path));
}

fn agent_args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "eval", "--agent", "a.txt", "a_gt.txt", "--agent", "b.txt", "b_gt.txt",
    ];
    args.extend_from_slice(extra);
    args
}

#[test]
fn two_agents_print_a_table_and_the_same_numbers_as_json() {
    let ws = Workspace::new();
    write_two_agents(&ws);
    let text = ws.rslam(&agent_args(&[])).success();
    for fragment in [
        "2 agents, 270 pairs (with SE(3) Umeyama alignment)",
        "agent     pairs       ATE own       SSE own     ATE joint     SSE joint",
        "joint  ",
        "joint alignment (p_gt = scale * R * p_est + t)",
    ] {
        assert!(text.contains(fragment), "missing '{fragment}' in:\n{text}");
    }
    let json = json_of(&ws.rslam(&agent_args(&["--json"])).success());
    assert_eq!(json["align"], "se3");
    let row = |name: &str| {
        text.lines()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("no row '{name}' in:\n{text}"))
            .split_whitespace()
            .skip(1)
            .map(str::to_string)
            .collect::<Vec<_>>()
    };
    let six = |v: &serde_json::Value| format!("{:.6}", v.as_f64().unwrap());
    for (i, name) in ["a", "b"].iter().enumerate() {
        let agent = &json["agents"][i];
        assert_eq!(agent["name"], *name);
        // Each agent on its own is exact up to a rigid motion.
        assert!(agent["ate"]["rmse"].as_f64().unwrap() < 1e-6, "{agent}");
        assert_eq!(
            row(name),
            [
                agent["pairs"].to_string(),
                six(&agent["ate"]["rmse"]),
                six(&agent["ate"]["sse"]),
                six(&agent["ate_joint"]["rmse"]),
                six(&agent["ate_joint"]["sse"]),
            ]
        );
    }
    // Together they disagree by the shift: it shows in the joint ATE, not in b's own.
    let joint = &json["joint"];
    assert!(joint["ate"]["rmse"].as_f64().unwrap() > 0.1, "{joint}");
    assert_eq!(joint["pairs"], 270);
    assert_eq!(
        row("joint"),
        [
            "270".to_string(),
            "-".to_string(),
            "-".to_string(),
            six(&joint["ate"]["rmse"]),
            six(&joint["ate"]["sse"]),
        ]
    );
    let n = 270.0;
    let rmse = joint["ate"]["rmse"].as_f64().unwrap();
    let sse = joint["ate"]["sse"].as_f64().unwrap();
    assert!((sse - n * rmse * rmse).abs() < 1e-9, "SSE = n * RMSE^2");
}

#[test]
fn a_folder_per_agent_gives_the_same_evaluation_as_pairs() {
    let ws = Workspace::new();
    write_two_agents(&ws);
    for name in ["a", "b"] {
        let est = std::fs::read_to_string(ws.path(&format!("{name}.txt"))).unwrap();
        let gt = std::fs::read_to_string(ws.path(&format!("{name}_gt.txt"))).unwrap();
        ws.write(&format!("agents/{name}/estimate.txt"), &est);
        ws.write(&format!("agents/{name}/groundtruth.txt"), &gt);
    }
    let from_pairs = ws
        .rslam(&agent_args(&["--json", "--align", "sim3"]))
        .success();
    let from_folder = ws
        .rslam(&["eval", "--agents", "agents", "--json", "--align", "sim3"])
        .success();
    assert_eq!(json_of(&from_pairs), json_of(&from_folder));
}

#[test]
fn bad_agent_input_is_a_one_line_error_naming_the_file_or_flag() {
    let ws = Workspace::new();
    write_two_agents(&ws);
    let err = ws
        .rslam(&["eval", "--agent", "a.txt", "a_gt.txt", "--agent", "b.txt"])
        .fails_with(2, &["--agent"]);
    assert!(err.contains("2 values required"), "{err}");
    let err = ws
        .rslam(&[
            "eval", "--agent", "a.txt", "a_gt.txt", "--agent", "gone.txt", "b_gt.txt",
        ])
        .fails_with(2, &["agent gone (gone.txt against b_gt.txt): gone.txt"]);
    assert_eq!(err.lines().count(), 1, "{err}");

    ws.write("agents/a/estimate.txt", &tum(50, 0.0, identity));
    ws.write("agents/a/traj.txt", &tum(50, 0.0, identity));
    ws.write("agents/b/groundtruth.txt", &tum(50, 0.0, identity));
    let err = ws
        .rslam(&["eval", "--agents", "agents"])
        .fails_with(2, &["agents/b/estimate.txt: no such file"]);
    assert_eq!(err.lines().count(), 1, "{err}");

    ws.write("agents/b/estimate.txt", &tum(50, 100.0, identity));
    let err = ws.rslam(&["eval", "--agents", "agents"]).fails_with(
        2,
        &["agent b (agents/b/estimate.txt against agents/b/groundtruth.txt): no matching timestamps"],
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    ws.rslam(&["eval", "a.txt", "a_gt.txt", "--agents", "agents"])
        .fails_with(2, &["cannot be used with"]);
}
