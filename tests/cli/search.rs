//! `rslam suite search` with a stand-in method whose failure rule is known and measured from the
//! pixels (`noise_method.py`: it fails when the frames' noise, estimated against the clean
//! frames, exceeds a threshold): the search finds the severity where gaussian_noise's σ crosses
//! the threshold to within the resolution, by bisection, for a monotone and for a noisy method;
//! a family that never breaks it is null, shown as "> 5"; a killed search and a sharded one
//! give the same profile.

use std::time::Duration;

use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

const METHOD: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../tests/cli/noise_method.py"
);
/// gaussian_noise's σ at severity 3.3: 0.18 + 0.3 × (0.26 − 0.18), the table's rows at 3 and 4.
const THRESHOLD: f64 = 0.204;
const BREAKS_AT: f64 = 3.3;
const RESOLUTION: f64 = 0.1;

fn workspace() -> Workspace {
    let ws = Workspace::new();
    ws.write(
        "study/suite.toml",
        &format!("seed = 5\n[defaults]\nframes = 6\ncamera = \"{SMALL_CAMERA}\"\n"),
    );
    ws.render_room0(
        "clean",
        &["--frames", "6", "--format", "tum", "--camera", SMALL_CAMERA],
        None,
    );
    ws
}

/// A method file running `noise_method.py`, failing at random near the threshold with `spread`.
fn method(ws: &Workspace, name: &str, spread: f64, repeats: usize) -> String {
    let clean = ws.path("clean").display().to_string();
    let path = format!("methods/{name}.toml");
    ws.write(
        &path,
        &format!(
            "name = \"{name}\"\nreads = \"tum\"\ntimeout_s = 120\nrepeats = {repeats}\ncommand = \
             [\"python3\", \"{METHOD}\", \"{{dataset}}\", \"{{estimate}}\", \"{clean}\", \"{THRESHOLD}\", \
             \"{spread}\", \"{{sequence}}\", \"{{repeat}}\"]\n"
        ),
    );
    path
}

fn search_args<'a>(method: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "suite",
        "search",
        "study",
        "--methods",
        method,
        "--families",
        "gaussian_noise,contrast",
        "--scenes",
        "room0",
        "--criterion",
        "failed",
        "--resolution",
        "0.1",
    ];
    args.extend(extra);
    args
}

fn profile(ws: &Workspace) -> serde_json::Value {
    json_file(ws, "study/search/profile.json")
}

#[test]
fn bisection_finds_the_known_breaking_severity_and_never_breaking_is_null() {
    let ws = workspace();
    let method = method(&ws, "noise", 0.0, 1);
    let out = stderr_of(&ws, &search_args(&method, &[]));
    let found = &profile(&ws)["noise"]["gaussian_noise"]["room0"];
    let breaking = found["breaking_severity"].as_f64().unwrap();
    let low = found["low"].as_f64().unwrap();
    assert!(
        low < BREAKS_AT && BREAKS_AT <= breaking + 0.02 && breaking - low <= RESOLUTION + 1e-9,
        "{found} {out}"
    );
    assert!((breaking - BREAKS_AT).abs() <= RESOLUTION, "{found}");
    // 0, 5, then bisections down to 0.1: at most 8 severities, 1 run each; not a grid scan.
    assert!(found["runs"].as_u64().unwrap() <= 8, "{found}");
    let probes: Vec<&str> = out
        .lines()
        .filter(|l| l.contains("gaussian_noise room0 at"))
        .collect();
    assert!(probes.iter().any(|l| l.contains(" at 2.5: holds")), "{out}");
    assert!(
        probes.iter().any(|l| l.contains(" at 3.75: breaks")),
        "{out}"
    );
    let never = &profile(&ws)["noise"]["contrast"]["room0"];
    assert!(never["breaking_severity"].is_null(), "{never}");
    assert_eq!(never["low"], 5.0);
    assert_eq!(never["runs"], 2);
    let csv = std::fs::read_to_string(ws.path("study/search/profile.csv")).unwrap();
    assert!(csv.contains("noise,contrast,room0,>5,5,,2\n"), "{csv}");
    let html = std::fs::read_to_string(ws.path("study/search/report.html")).unwrap();
    assert!(html.contains("&gt; 5") && html.contains("<svg"));
    // Each severity tried is an ephemeral sequence: what evaluation reads is kept, no frames.
    let kept = ws.path("study/search/datasets/room0__gaussian_noise-2.5");
    assert!(kept.join("groundtruth.txt").is_file() && !kept.join("rgb").exists());
    // search/ is a suite folder of its own: its suite.toml lists every sequence made.
    let listed = std::fs::read_to_string(ws.path("study/search/suite.toml")).unwrap();
    assert!(
        listed.contains("name = \"room0__gaussian_noise-2.5\""),
        "{listed}"
    );
    ws.rslam(&["suite", "status", "study/search"]).success();
    ws.rslam(&["suite", "report", "study/search"]).success();
    assert!(ws.path("study/search/report/report.html").is_file());
    // A second run finds every run recorded, runs nothing and writes the same profile.
    let records = run_records(&ws);
    let before = std::fs::read_to_string(ws.path("study/search/profile.json")).unwrap();
    ws.rslam(&search_args(&method, &[])).success();
    assert_eq!(run_records(&ws), records);
    let after = std::fs::read_to_string(ws.path("study/search/profile.json")).unwrap();
    assert_eq!(after, before);
}

/// Runs `rslam ARGS`, which must succeed; its stderr (the search's log).
fn stderr_of(ws: &Workspace, args: &[&str]) -> String {
    let run = ws.rslam(args);
    run.success();
    run.stderr()
}

/// Every run record of the search with its modification time.
fn run_records(ws: &Workspace) -> Vec<(std::path::PathBuf, std::time::SystemTime)> {
    let mut records = Vec::new();
    let runs = ws.path("study/search/runs");
    for method in std::fs::read_dir(runs).unwrap().flatten() {
        for sequence in std::fs::read_dir(method.path()).unwrap().flatten() {
            for file in std::fs::read_dir(sequence.path()).unwrap().flatten() {
                let modified = file.metadata().unwrap().modified().unwrap();
                records.push((file.path(), modified));
            }
        }
    }
    records.sort();
    records
}

#[test]
fn a_noisy_method_is_found_near_its_threshold_by_the_median_of_repeats() {
    let ws = workspace();
    // P(fail) goes from 12% to 88% over σ ± 0.006, about ± 0.075 in severity.
    let method = method(&ws, "noisy", 0.003, 5);
    ws.rslam(&search_args(&method, &["--families", "gaussian_noise"]))
        .success();
    let found = &profile(&ws)["noisy"]["gaussian_noise"]["room0"];
    let breaking = found["breaking_severity"].as_f64().unwrap();
    assert!((breaking - BREAKS_AT).abs() <= 2.0 * RESOLUTION, "{found}");
    assert_eq!(found["runs"].as_u64().unwrap() % 5, 0, "{found}");
}

#[test]
fn a_killed_search_and_a_sharded_one_give_the_same_profile() {
    let whole = workspace();
    let method_path = method(&whole, "noise", 0.0, 1);
    whole.rslam(&search_args(&method_path, &[])).success();
    let reference = std::fs::read_to_string(whole.path("study/search/profile.json")).unwrap();

    let killed = workspace();
    let method_path = method(&killed, "noise", 0.0, 1);
    let mut child = killed.spawn_rslam(&search_args(&method_path, &[]));
    let runs = killed.path("study/search/runs/noise");
    let started = std::time::Instant::now();
    while std::fs::read_dir(&runs).map_or(0, |d| d.count()) < 3 {
        assert!(
            started.elapsed() < Duration::from_secs(120),
            "no runs recorded"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(!killed.path("study/search/profile.json").exists());
    killed.rslam(&search_args(&method_path, &[])).success();
    let resumed = std::fs::read_to_string(killed.path("study/search/profile.json")).unwrap();
    assert_eq!(resumed, reference);

    let sharded = workspace();
    let method_path = method(&sharded, "noise", 0.0, 1);
    for shard in ["0/2", "1/2"] {
        let out = stderr_of(&sharded, &search_args(&method_path, &["--shard", shard]));
        assert!(out.contains("without --shard writes the profile"), "{out}");
    }
    let records = run_records(&sharded);
    sharded.rslam(&search_args(&method_path, &[])).success();
    assert_eq!(
        run_records(&sharded),
        records,
        "the shards ran every search"
    );
    let combined = std::fs::read_to_string(sharded.path("study/search/profile.json")).unwrap();
    assert_eq!(combined, reference);
}

#[test]
fn bad_options_are_refused_in_one_line() {
    let ws = Workspace::new();
    ws.write(
        "m.toml",
        "name = \"m\"\nreads = \"tum\"\ncommand = [\"true\"]\ntimeout_s = 1\n",
    );
    let base = [
        "suite",
        "search",
        "s",
        "--methods",
        "m.toml",
        "--scenes",
        "room0",
    ];
    let run = |extra: &[&str]| ws.rslam(&[&base[..], extra].concat());
    run(&["--families", "fgo"]).fails_with(2, &["--families", "'fgo'", "gaussian_noise"]);
    run(&["--families", "fog", "--criterion", "sr>0.5"]).fails_with(2, &["criterion 'sr>0.5'"]);
    run(&["--families", "fog", "--resolution", "0"]).fails_with(2, &["--resolution 0"]);
    run(&["--families", "fog", "--scenes", "nowhere"]).fails_with(2, &["nowhere"]);
    // A scheduler's search job is checked when it is written, not in each task's log.
    std::fs::create_dir_all(ws.path("s")).unwrap();
    let slurm = |extra: &[&str]| {
        let base = [
            "suite",
            "slurm",
            "s",
            "--tasks",
            "2",
            "--search",
            "--methods",
            "m.toml",
        ];
        ws.rslam(&[&base[..], extra].concat())
    };
    slurm(&["--families", "fgo", "--scenes", "room0"]).fails_with(2, &["--families", "'fgo'"]);
    slurm(&[
        "--families",
        "fog",
        "--scenes",
        "room0",
        "--criterion",
        "ate<3",
    ])
    .fails_with(2, &["criterion 'ate<3'"]);
    let script = slurm(&["--families", "fog", "--scenes", "room0"]).success();
    let text = std::fs::read_to_string(script.trim()).unwrap();
    assert!(
        text.contains(" suite search ") && text.contains("--families fog"),
        "{text}"
    );
}

/// `rslam suite search s` of a method that returns the ground truth (so never breaks) with
/// `repeats` runs a sequence, on 5 frames of room0 under `family`; must succeed.
fn search_oracle(ws: &Workspace, repeats: usize, family: &str, extra: &[&str]) {
    ws.write(
        "oracle.toml",
        &format!(
            "name = \"oracle\"\nreads = \"tum\"\ntimeout_s = 60\nrepeats = {repeats}\ncommand = \
             [\"cp\", \"{{dataset}}/groundtruth.txt\", \"{{estimate}}\"]\n"
        ),
    );
    let mut args = vec![
        "suite",
        "search",
        "s",
        "--methods",
        "oracle.toml",
        "--families",
        family,
        "--scenes",
        "room0",
        "--frames",
        "5",
        "--criterion",
        "failed",
    ];
    args.extend(extra);
    ws.rslam(&args).success();
}

fn json_file(ws: &Workspace, rel: &str) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(ws.path(rel)).unwrap()).unwrap()
}

#[test]
fn keep_leaves_the_frames_of_every_severity_tried() {
    let ws = Workspace::new();
    search_oracle(&ws, 1, "fog", &["--resolution", "1", "--keep"]);
    for name in ["room0__clean", "room0__fog-5"] {
        let rgb = ws.path(&format!("s/search/datasets/{name}/rgb"));
        assert_eq!(std::fs::read_dir(&rgb).unwrap().count(), 5, "{name}");
    }
    let found = &json_file(&ws, "s/search/profile.json")["oracle"]["fog"]["room0"];
    assert!(found["breaking_severity"].is_null(), "{found}");
}

#[test]
fn seeds_make_one_sequence_per_seed_at_every_severity() {
    let ws = Workspace::new();
    search_oracle(&ws, 2, "gaussian_noise", &["--seeds", "2"]);
    let found = &json_file(&ws, "s/search/profile.json")["oracle"]["gaussian_noise"]["room0"];
    // Clean and 5, each 2 sequences × 2 repeats.
    assert_eq!(found["runs"], 8, "{found}");
    let seed = |name: &str| {
        json_file(&ws, &format!("s/search/datasets/{name}/rslam.json"))["seed"].clone()
    };
    assert_ne!(
        seed("room0__gaussian_noise-5"),
        seed("room0__gaussian_noise-5-seed1")
    );
    assert!(ws
        .path("s/search/runs/oracle/room0__clean-seed1/1.json")
        .is_file());
}
