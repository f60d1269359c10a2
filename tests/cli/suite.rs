//! `rslam suite`: shards made by two processes at once give the bytes of one process; a killed
//! run resumes to the same bytes; status tells complete from missing and conflicting sequences;
//! a suite that cannot fit is refused before anything is written; bad suite files are named.

use std::collections::BTreeSet;
use std::process::Command;

use crate::dataset_check::{assert_same_tree, tree};
use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;
use crate::resume::kill_mid_run;

/// Six sequences over three scenes, every kind of perturbation, tiny frames.
fn six_sequences() -> String {
    format!(
        r#"seed = 3
[defaults]
frames = 6
camera = "{SMALL_CAMERA}"

[[sequence]]
name = "room0__clean"
scene = "room0"

[[sequence]]
name = "room0__fog-3"
scene = "room0"
perturb = "fog:3,depth_missing:2"

[[sequence]]
name = "room0__rot-1-trans-0.025"
scene = "room0"
perturb = "rot:1,trans:0.025"

[[sequence]]
name = "office0__clean"
scene = "office0"
format = "tum"

[[sequence]]
name = "office0__fast-2"
scene = "office0"
perturb = "fast:2"

[[sequence]]
name = "room1__misalign-2-dynamic"
scene = "room1"
perturb = "misalign:2@dynamic"
"#
    )
}

fn suite_in(ws: &Workspace, text: &str) {
    ws.write("suite/suite.toml", text);
}

/// The sequences each run made, from the suite's timing log.
fn made_runs(ws: &Workspace) -> Vec<String> {
    let text = std::fs::read_to_string(ws.path("suite/logs/timings.jsonl")).unwrap_or_default();
    text.lines()
        .map(|line| {
            let v: serde_json::Value = serde_json::from_str(line).unwrap();
            v["sequence"].as_str().unwrap().to_string()
        })
        .collect()
}

/// N of the summary line "…, N made now, …".
fn made_now(log: &str) -> usize {
    let before = log.split(" made now").next().unwrap_or("");
    before
        .rsplit(' ')
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or(0)
}

#[test]
fn two_shards_at_once_make_every_sequence_once_with_the_bytes_of_one_process() {
    let whole = Workspace::new();
    suite_in(&whole, &six_sequences());
    whole.rslam(&["suite", "run", "suite"]).success();

    let sharded = Workspace::new();
    suite_in(&sharded, &six_sequences());
    let shard = |i: &str| {
        Command::new(env!("CARGO_BIN_EXE_rslam"))
            .args(["suite", "run", "suite", "--shard", i])
            .current_dir(sharded.path(""))
            .output()
            .unwrap()
    };
    let (first, second) = std::thread::scope(|s| {
        let a = s.spawn(|| shard("0/2"));
        let b = s.spawn(|| shard("1/2"));
        (a.join().unwrap(), b.join().unwrap())
    });
    for (output, name) in [(&first, "0/2"), (&second, "1/2")] {
        let log = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "shard {name}: {log}");
        assert!(log.contains(&format!("shard {name}")), "{log}");
        assert!(
            made_now(&log) > 0,
            "each shard has sequences of its own: {log}"
        );
    }
    let made = made_runs(&sharded);
    let distinct: BTreeSet<&String> = made.iter().collect();
    assert_eq!(
        (made.len(), distinct.len()),
        (6, 6),
        "each sequence made exactly once: {made:?}"
    );
    for name in [
        "room0__clean",
        "office0__fast-2",
        "room1__misalign-2-dynamic",
    ] {
        assert!(distinct.contains(&name.to_string()), "{name}");
    }
    assert_same_tree(
        &whole.path("suite/datasets"),
        &sharded.path("suite/datasets"),
    );

    let again = sharded.rslam(&["suite", "run", "suite"]);
    again.success();
    assert!(
        again.stderr().contains("6 were complete, 0 made now"),
        "{}",
        again.stderr()
    );
    assert_eq!(
        made_runs(&sharded).len(),
        6,
        "a complete suite makes nothing"
    );
    let status = sharded.rslam(&["suite", "status", "suite"]).success();
    assert!(
        status.contains("6 complete, 0 partial, 0 missing, 0 conflict"),
        "{status}"
    );
}

#[test]
fn a_killed_suite_run_resumes_to_the_bytes_of_an_uninterrupted_one() {
    let text = format!(
        r#"[defaults]
camera = "{SMALL_CAMERA}"
[[sequence]]
name = "room0__long"
scene = "room0"
frames = 300
perturb = "gaussian_noise:3@dynamic,depth_missing:2,misalign:3@dynamic"
[[sequence]]
name = "room1__short"
scene = "room1"
frames = 4
"#
    );
    let whole = Workspace::new();
    suite_in(&whole, &text);
    whole
        .rslam(&["suite", "run", "suite", "--shard", "0/1"])
        .success();

    let killed = Workspace::new();
    suite_in(&killed, &text);
    kill_mid_run(
        &killed,
        &["suite", "run", "suite"],
        "suite/datasets/room0__long",
        "results",
        "frame",
    );
    let status = killed.rslam(&["suite", "status", "suite"]);
    assert_eq!(status.output.status.code(), Some(1), "{}", status.stdout());
    assert!(status.stdout().contains("1 partial"), "{}", status.stdout());
    let resumed = killed.rslam(&["suite", "run", "suite"]);
    resumed.success();
    assert!(
        resumed.stderr().contains("room0__long: resumed"),
        "{}",
        resumed.stderr()
    );
    assert_same_tree(
        &whole.path("suite/datasets"),
        &killed.path("suite/datasets"),
    );
    killed.rslam(&["suite", "status", "suite"]).success();
}

#[test]
fn status_names_conflicts_and_run_leaves_them_alone_unless_forced() {
    let ws = Workspace::new();
    let one = |perturb: &str| {
        format!(
            "[[sequence]]\nname = \"room0__x\"\nscene = \"room0\"\nframes = 3\ncamera = \"{SMALL_CAMERA}\"\nperturb = \"{perturb}\"\n"
        )
    };
    suite_in(&ws, &one("fog:1"));
    let missing = ws.rslam(&["suite", "status", "suite", "--json"]);
    assert_eq!(missing.output.status.code(), Some(1));
    let json: serde_json::Value = serde_json::from_str(&missing.stdout()).unwrap();
    assert_eq!(json["status"]["sequences"][0]["state"], "missing");
    ws.rslam(&["suite", "run", "suite"]).success();
    let made = tree(&ws.path("suite/datasets/room0__x"));

    suite_in(&ws, &one("fog:2"));
    let status = ws.rslam(&["suite", "status", "suite"]);
    assert_eq!(status.output.status.code(), Some(1));
    assert!(
        status.stdout().contains(
            "conflict: room0__x: holds the finished output of another job (`rslam render"
        ),
        "{}",
        status.stdout()
    );
    let run = ws.rslam(&["suite", "run", "suite"]);
    assert_eq!(run.output.status.code(), Some(1), "{}", run.stderr());
    assert!(
        run.stderr().contains("left alone: room0__x"),
        "{}",
        run.stderr()
    );
    assert_eq!(
        tree(&ws.path("suite/datasets/room0__x")),
        made,
        "left untouched"
    );

    ws.rslam(&["suite", "run", "suite", "--force"]).success();
    let json: serde_json::Value =
        serde_json::from_str(&ws.rslam(&["suite", "status", "suite", "--json"]).success()).unwrap();
    assert_eq!(json["status"]["sequences"][0]["state"], "complete");
    let manifest = crate::dataset_check::manifest(&ws.path("suite/datasets/room0__x"));
    assert_eq!(manifest.perturbation, "fog:2");
}

/// The suite asks the job's rule whether a sequence is finished: one whose listed file went
/// missing is partial, not complete, and the next run makes that file again, to the same bytes.
#[test]
fn a_sequence_missing_a_listed_file_is_partial_and_the_next_run_restores_it() {
    let ws = Workspace::new();
    suite_in(
        &ws,
        &format!(
            "[[sequence]]\nname = \"room0__x\"\nscene = \"room0\"\nframes = 3\ncamera = \"{SMALL_CAMERA}\"\nperturb = \"fog:1\"\n"
        ),
    );
    ws.rslam(&["suite", "run", "suite"]).success();
    let dir = ws.path("suite/datasets/room0__x");
    let made = tree(&dir);
    std::fs::remove_file(dir.join("results/frame000001.jpg")).unwrap();
    let status = ws.rslam(&["suite", "status", "suite"]);
    assert_eq!(status.output.status.code(), Some(1), "{}", status.stdout());
    assert!(
        status.stdout().contains("0 complete, 1 partial"),
        "{}",
        status.stdout()
    );
    let resumed = ws.rslam(&["suite", "run", "suite"]);
    resumed.success();
    assert!(
        resumed.stderr().contains("room0__x: resumed"),
        "{}",
        resumed.stderr()
    );
    assert_eq!(tree(&dir), made, "the same bytes as the first run");
}

#[test]
fn a_suite_that_cannot_fit_is_refused_before_anything_is_written() {
    let ws = Workspace::new();
    suite_in(
        &ws,
        "[[sequence]]\nname = \"room0__huge\"\nscene = \"room0\"\ncamera = \"16000,16000,8000,8000,7999.5,7999.5\"\nframes = 1000000\n",
    );
    let plan = ws.rslam(&["suite", "status", "suite", "--plan"]);
    assert!(
        plan.stdout().contains("NOT ENOUGH SPACE"),
        "{}",
        plan.stdout()
    );
    ws.rslam(&["suite", "run", "suite"])
        .fails_with(2, &["suite/datasets", "needed for 1 sequence(s)", "free"]);
    assert!(!ws.path("suite/datasets/room0__huge").exists());
}

#[test]
fn bad_suite_files_are_named_with_their_line() {
    let ws = Workspace::new();
    let cases = [
        ("[[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\nperturbb = \"fog:1\"\n", ":4:", "unknown field `perturbb`"),
        ("[[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\n\n[[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\n", ":5:", "listed twice"),
        ("[[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\nperturb = \"fog:9\"\n", ":1:", "sequence 'room0__a': perturb"),
        ("[[sequence]]\nname = \"a\"\nscene = \"room0\"\n", ":1:", "expected <scene>__<setting>"),
        ("[[sequence]]\nname = \"m__a\"\nscene = \"mesh.ply\"\ntraj = \"t.txt\"\n", ":1:", "scene 'mesh.ply': no such file"),
        ("[[sequence]]\nname = \"m__a\"\nscene = \"kitchen\"\n", ":1:", "neither a built-in scene"),
    ];
    for (text, line, fragment) in cases {
        suite_in(&ws, text);
        ws.rslam(&["suite", "status", "suite"])
            .fails_with(2, &[&format!("suite.toml{line}"), fragment]);
    }
    ws.rslam(&["suite", "status", "nowhere"])
        .fails_with(2, &["nowhere/suite.toml", "suite init"]);
    suite_in(&ws, &six_sequences());
    ws.rslam(&["suite", "run", "suite", "--shard", "2/2"])
        .fails_with(2, &["--shard", "0 <= index < count"]);
}

#[test]
fn init_writes_the_preset_and_refuses_to_overwrite_it() {
    let ws = Workspace::new();
    let out = ws
        .rslam(&[
            "suite",
            "init",
            "--preset",
            "robust-slam",
            "--scenes",
            "room0,office3",
            "--frames",
            "50",
            "--out",
            "s",
        ])
        .success();
    assert!(out.contains("250 sequences"), "{out}");
    let status = ws.rslam(&["suite", "status", "s", "--plan"]);
    assert_eq!(status.output.status.code(), Some(1));
    let text = status.stdout();
    assert!(
        text.contains("0 complete, 0 partial, 250 missing"),
        "{text}"
    );
    assert!(text.contains("plan: 12290 frames in all"), "{text}");
    ws.rslam(&["suite", "init", "--preset", "mini", "--out", "s"])
        .fails_with(2, &["s/suite.toml", "already exists"]);
}

#[test]
fn the_slurm_script_runs_the_suite_per_array_task() {
    let ws = Workspace::new();
    suite_in(&ws, &six_sequences());
    let path = ws
        .rslam(&[
            "suite",
            "slurm",
            "suite",
            "--tasks",
            "3",
            "--throttle",
            "2",
            "--sbatch-arg=--time=1:00:00",
        ])
        .success();
    let text = std::fs::read_to_string(path.trim()).unwrap();
    assert!(
        text.contains("#SBATCH --array=0-2%2\n#SBATCH --output="),
        "{text}"
    );
    assert!(text.contains("#SBATCH --time=1:00:00\n"), "{text}");
    let last = text.lines().last().unwrap();
    assert!(
        last.starts_with("exec /") && last.contains("rslam suite run /"),
        "{last}"
    );

    // What a task of that array does: its shard from Slurm's variables.
    let task = Command::new(env!("CARGO_BIN_EXE_rslam"))
        .args(["suite", "run", "suite"])
        .env("SLURM_ARRAY_TASK_ID", "1")
        .env("SLURM_ARRAY_TASK_COUNT", "3")
        .current_dir(ws.path(""))
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&task.stderr);
    assert!(
        task.status.success() && log.contains("shard 1/3 (Slurm array task)"),
        "{log}"
    );
}

#[test]
fn a_hand_written_suite_takes_user_meshes_and_paths_relative_to_it() {
    let ws = Workspace::new();
    suite_in(
        &ws,
        &format!(
            "[[sequence]]\nname = \"mine__clean\"\nscene = \"room1.ply\"\ntraj = \"room1.txt\"\nframes = 3\ncamera = \"{SMALL_CAMERA}\"\n"
        ),
    );
    ws.rslam(&["scene", "export", "room1", "--out", "suite/room1.ply"])
        .success();
    ws.rslam(&["scene", "traj", "room1", "--out", "suite/room1.txt"])
        .success();
    ws.rslam(&["suite", "run", "suite"]).success();
    let manifest = crate::dataset_check::manifest(&ws.path("suite/datasets/mine__clean"));
    assert_eq!(manifest.frame_count, 3);
    assert_eq!(
        manifest.command[..6],
        [
            "rslam",
            "render",
            "--scene",
            "room1.ply",
            "--traj",
            "room1.txt"
        ]
    );
    ws.rslam(&["suite", "status", "suite"]).success();
}

/// A `rig = "rgbd-imu"` row is the `rgbd-imu` render: the TUM layout with the IMU, the body's
/// ground truth and ORB-SLAM3's RGB-D-inertial settings beside it, the same bytes as the render
/// command the suite records.
#[test]
fn an_rgbd_imu_row_makes_the_rgbd_imu_dataset() {
    let ws = Workspace::new();
    ws.write(
        "suite/suite.toml",
        &format!(
            "[[sequence]]\nname = \"room0__imu\"\nscene = \"room0\"\nframes = 7\ncamera = \"{SMALL_CAMERA}\"\nrate = 30\nseed = 3\nformat = \"tum\"\nrig = \"rgbd-imu\"\nperturb = \"imu_noise:2\"\n"
        ),
    );
    ws.rslam(&["suite", "run", "suite"]).success();
    let dataset = ws.path("suite/datasets/room0__imu");
    for file in [
        "rgb.txt",
        "imu0/data.csv",
        "state_groundtruth_estimate0/data.csv",
        "orbslam3_rgbd_inertial.yaml",
    ] {
        assert!(dataset.join(file).is_file(), "{file}");
    }
    ws.rslam(&[
        "render",
        "--scene",
        "room0",
        "--frames",
        "7",
        "--rig",
        "rgbd-imu",
        "--camera",
        SMALL_CAMERA,
        "--rate",
        "30",
        "--format",
        "tum",
        "--seed",
        "3",
        "--perturb",
        "imu_noise:2",
        "--out",
        "by_hand",
    ])
    .success();
    let (suite, by_hand) = (tree(&dataset), tree(&ws.path("by_hand")));
    let content = |t: &std::collections::BTreeMap<String, Vec<u8>>| -> BTreeSet<String> {
        t.keys()
            .filter(|k| !k.starts_with("rslam."))
            .cloned()
            .collect()
    };
    assert_eq!(content(&suite), content(&by_hand));
    for key in content(&suite) {
        assert_eq!(suite[&key], by_hand[&key], "{key}");
    }
}
