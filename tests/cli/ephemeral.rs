//! `rslam suite bench --ephemeral` and `rslam suite regen`: a suite benched ephemerally gives
//! the runs and report of one benched with its datasets kept, while its folder never holds more
//! than the frames in flight; a deleted sequence is remade byte for byte; a killed bench goes on
//! without making or running again what was finished, and leaves no frames behind.

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use crate::dataset_check::{assert_same_tree, tree};
use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

const SETTINGS: [(&str, &str); 6] = [
    ("clean", ""),
    ("fog-3", "fog:3"),
    ("noise-2", "gaussian_noise:2"),
    ("blur-2", "motion_blur:2"),
    ("depth-2", "depth_noise:2"),
    ("dark-3", "brightness:3"),
];

fn suite(ws: &Workspace, dir: &str) {
    let mut text = format!(
        "seed = 3\n[defaults]\nframes = 6\nformat = \"tum\"\ncamera = \"{SMALL_CAMERA}\"\n"
    );
    for (setting, spec) in SETTINGS {
        text.push_str(&format!(
            "[[sequence]]\nname = \"room0__{setting}\"\nscene = \"room0\"\nperturb = \"{spec}\"\n"
        ));
    }
    ws.write(&format!("{dir}/suite.toml"), &text);
}

/// A method that logs a digest of every colour and depth frame it was given (so that two
/// benches can be seen to have run on the same bytes), then returns the ground truth.
fn frame_digest_method(ws: &Workspace, sleep_s: f64) -> String {
    let script = format!(
        "sleep {sleep_s}; cat \"$1\"/rgb/*.png \"$1\"/depth/*.png | md5sum >&2; cp \"$1\"/groundtruth.txt \"$2\""
    );
    ws.write(
        "methods/digest.toml",
        &format!(
            "name = \"digest\"\nreads = \"tum\"\ncommand = [\"sh\", \"-c\", {script:?}, \"sh\", \"{{dataset}}\", \"{{estimate}}\"]\ntimeout_s = 60\nrepeats = 2\n"
        ),
    );
    "methods/digest.toml".into()
}

fn bytes_under(dir: &Path) -> u64 {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    entries
        .flatten()
        .map(|e| match e.metadata() {
            Ok(m) if m.is_dir() => bytes_under(&e.path()),
            Ok(m) => m.len(),
            Err(_) => 0,
        })
        .sum()
}

fn frame_files(dir: &Path) -> Vec<String> {
    tree(dir)
        .into_keys()
        .filter(|f| f.ends_with(".png") || f.ends_with(".jpg"))
        .collect()
}

/// A run record without what differs between two runs of the same thing (wall time, memory),
/// its paths relative to the suite folder.
fn record(suite: &Path, method: &str, sequence: &str, repeat: usize) -> serde_json::Value {
    let path = suite.join(format!("runs/{method}/{sequence}/{repeat}.json"));
    let text = std::fs::read_to_string(&path).unwrap();
    let root = suite.canonicalize().unwrap().display().to_string();
    let mut record: serde_json::Value =
        serde_json::from_str(&text.replace(&root, "SUITE")).unwrap();
    for volatile in ["seconds", "peak_rss_mb"] {
        record.as_object_mut().unwrap().remove(volatile);
    }
    record
}

#[test]
fn an_ephemeral_bench_gives_the_runs_of_a_kept_one_within_the_disk_of_its_jobs() {
    let ws = Workspace::new();
    let method = frame_digest_method(&ws, 0.0);
    suite(&ws, "kept");
    ws.rslam(&["suite", "run", "kept"]).success();
    ws.rslam(&["suite", "bench", "kept", "--methods", &method])
        .success();
    suite(&ws, "ephemeral");

    let jobs = 2;
    let peak = std::sync::atomic::AtomicU64::new(0);
    let running = AtomicBool::new(true);
    let bench = std::thread::scope(|scope| {
        scope.spawn(|| {
            while running.load(Ordering::SeqCst) {
                peak.fetch_max(bytes_under(&ws.path("ephemeral")), Ordering::SeqCst);
                std::thread::sleep(Duration::from_millis(5));
            }
        });
        let jobs = jobs.to_string();
        let args = [
            "suite",
            "bench",
            "ephemeral",
            "--ephemeral",
            "--methods",
            &method,
            "--jobs",
            &jobs,
        ];
        let bench = ws.rslam(&args);
        running.store(false, Ordering::SeqCst);
        bench
    });
    bench.success();
    assert!(
        bench.stderr().contains("6 sequence(s) used now")
            && bench.stderr().contains("12 runs succeeded, 0 failed now"),
        "{}",
        bench.stderr()
    );

    let (kept, ephemeral) = (ws.path("kept"), ws.path("ephemeral"));
    let largest = SETTINGS
        .iter()
        .map(|(s, _)| bytes_under(&kept.join(format!("datasets/room0__{s}"))))
        .max()
        .unwrap();
    let left = bytes_under(&ephemeral);
    let peak = peak.into_inner();
    assert!(
        peak <= (jobs as u64 + 1) * largest + left,
        "the folder held {peak} B; {jobs} jobs of sequences up to {largest} B and {left} B kept allow less"
    );
    assert!(
        left + largest < 6 * largest,
        "the bound is only a test if keeping every frame would break it"
    );
    assert!(frame_files(&ephemeral).is_empty(), "no frame is left");

    for (setting, _) in SETTINGS {
        let sequence = format!("room0__{setting}");
        for repeat in 0..2 {
            assert_eq!(
                record(&kept, "digest", &sequence, repeat),
                record(&ephemeral, "digest", &sequence, repeat),
                "{sequence} #{repeat}"
            );
            for file in ["txt", "log"] {
                let read = |suite: &Path| {
                    std::fs::read(suite.join(format!("runs/digest/{sequence}/{repeat}.{file}")))
                        .unwrap()
                };
                assert!(
                    read(&kept) == read(&ephemeral),
                    "{sequence} #{repeat}.{file}: the method saw other frames"
                );
            }
        }
    }
    let status = ws.rslam(&["suite", "status", "ephemeral"]).success();
    assert!(status.contains("0 complete, 6 frames-deleted"), "{status}");
    let plan = ws
        .rslam(&["suite", "status", "ephemeral", "--plan", "--jobs", "2"])
        .success();
    assert!(
        plan.contains("ephemeral (suite bench --ephemeral --jobs 2)")
            && plan.contains("runs: measured over 12 finished run(s) on 6 sequence(s)"),
        "{plan}"
    );

    for suite in ["kept", "ephemeral"] {
        ws.rslam(&["suite", "report", suite]).success();
    }
    let report = |suite: &Path| {
        let text = std::fs::read_to_string(suite.join("report/report.json")).unwrap();
        serde_json::from_str::<serde_json::Value>(&text).unwrap()["runs"].clone()
    };
    assert_eq!(report(&kept), report(&ephemeral));

    let name = "room0__fog-3";
    let dataset = format!("ephemeral/datasets/{name}");
    ws.rslam(&["verify", &dataset])
        .fails_with(2, &["frames were deleted after use", "suite regen"]);
    let regen = ws.rslam(&["suite", "regen", "ephemeral", name]).success();
    assert!(
        regen.contains("every one equal to the kept checksums"),
        "{regen}"
    );
    ws.rslam(&["verify", &dataset]).success();
    assert_same_tree(&kept.join(format!("datasets/{name}")), &ws.path(&dataset));
    let status = ws.rslam(&["suite", "status", "ephemeral"]).success();
    assert!(status.contains("1 complete, 5 frames-deleted"), "{status}");
}

#[test]
fn a_killed_ephemeral_bench_goes_on_without_making_or_running_twice_what_was_finished() {
    let ws = Workspace::new();
    let method = frame_digest_method(&ws, 0.2);
    suite(&ws, "suite");
    let scratch = ws.path("scratch");
    let args = [
        "suite",
        "bench",
        "suite",
        "--ephemeral",
        "--methods",
        &method,
        "--scratch",
        "scratch",
    ];
    let mut child = ws.spawn_rslam(&args);
    let third = ws.path("suite/runs/digest/room0__noise-2/0.json");
    for _ in 0..2400 {
        if third.is_file() {
            break;
        }
        std::thread::sleep(Duration::from_millis(25));
    }
    child.kill().unwrap(); // SIGKILL: no handler runs, nothing is tidied up
    child.wait().unwrap();
    assert!(
        third.is_file(),
        "the bench did not get to the third sequence"
    );
    let finished: Vec<(String, String)> = tree(&ws.path("suite/runs"))
        .into_iter()
        .filter(|(f, _)| f.ends_with(".json"))
        .map(|(f, bytes)| (f, String::from_utf8(bytes).unwrap()))
        .collect();
    assert!(
        !frame_files(&scratch).is_empty(),
        "killed mid-sequence, its frames are still in scratch"
    );
    let timings_before = std::fs::read_to_string(ws.path("suite/logs/timings.jsonl")).unwrap();

    let again = ws.rslam(&args);
    again.success();
    for (file, text) in &finished {
        let now = std::fs::read_to_string(ws.path("suite/runs").join(file)).unwrap();
        assert_eq!(&now, text, "{file}: a finished run ran again");
    }
    let timings_after = std::fs::read_to_string(ws.path("suite/logs/timings.jsonl")).unwrap();
    let made_again: Vec<&str> = timings_after[timings_before.len()..]
        .lines()
        .filter(|line| line.contains("room0__clean") || line.contains("room0__fog-3"))
        .collect();
    assert!(
        made_again.is_empty(),
        "sequences whose runs were finished were made again: {made_again:?}"
    );
    assert!(
        again
            .stderr()
            .contains(&format!("{} were done before", finished.len())),
        "{}",
        again.stderr()
    );
    assert_eq!(
        tree(&ws.path("suite/runs"))
            .keys()
            .filter(|f| f.ends_with(".txt"))
            .count(),
        12,
        "every run finished"
    );
    assert!(frame_files(&ws.path("suite")).is_empty() && frame_files(&scratch).is_empty());
    assert!(
        !ws.path("suite/datasets/.kept-partial").exists(),
        "the kept files' gathering folder goes"
    );
    assert_eq!(
        std::fs::read_dir(&scratch).unwrap().count(),
        0,
        "the suite's scratch folder goes when it is done"
    );
    let status = ws.rslam(&["suite", "status", "suite"]).success();
    assert!(status.contains("6 frames-deleted"), "{status}");
}

#[test]
fn regen_refuses_a_row_that_no_longer_defines_the_kept_job() {
    let ws = Workspace::new();
    ws.write(
        "suite/suite.toml",
        &format!("[defaults]\nframes = 4\nformat = \"tum\"\ncamera = \"{SMALL_CAMERA}\"\n[[sequence]]\nname = \"room0__fog\"\nscene = \"room0\"\nperturb = \"fog:2\"\n"),
    );
    ws.rslam(&["suite", "run", "suite"]).success();
    ws.rslam(&["suite", "regen", "suite", "room0__nope"])
        .fails_with(2, &["NAME: 'room0__nope' is no sequence of suite"]);
    let text = std::fs::read_to_string(ws.path("suite/suite.toml")).unwrap();
    ws.write("suite/suite.toml", &text.replace("fog:2", "fog:4"));
    ws.rslam(&["suite", "regen", "suite", "room0__fog"]).fails_with(
        2,
        &["the row of 'room0__fog' in suite.toml no longer defines the job its kept manifest records (they differ in perturbation"],
    );
}

/// Culling reads a dataset's cameras; with its frames deleted they come from what it keeps, and
/// must be the same views in every layout.
#[test]
fn a_dataset_whose_frames_were_deleted_culls_to_the_same_views() {
    let ws = Workspace::new();
    ws.rslam(&["scene", "export", "room0", "--out", "room0.ply"])
        .success();
    for (layout, row, reads) in [
        (
            "replica",
            format!("camera = \"{SMALL_CAMERA}\"\n"),
            "replica",
        ),
        (
            "tum",
            format!("format = \"tum\"\ncamera = \"{SMALL_CAMERA}\"\n"),
            "tum",
        ),
        (
            "euroc",
            "format = \"euroc\"\nrig = \"stereo\"\n".to_string(),
            "euroc",
        ),
    ] {
        let text = format!(
            "[[sequence]]\nname = \"room0__{layout}\"\nscene = \"room0\"\nframes = 8\n{row}"
        );
        ws.write(&format!("kept-{layout}/suite.toml"), &text);
        ws.write(&format!("used-{layout}/suite.toml"), &text);
        let method = ws.write(
            &format!("methods/{layout}.toml"),
            &format!(
                "name = \"none\"\nreads = \"{reads}\"\ncommand = [\"true\"]\ntimeout_s = 30\n"
            ),
        );
        ws.rslam(&["suite", "run", &format!("kept-{layout}")])
            .success();
        let used = format!("used-{layout}");
        let method = method.display().to_string();
        ws.rslam(&["suite", "bench", &used, "--ephemeral", "--methods", &method])
            .success();
        let views = |suite: &str| {
            let dataset = format!("{suite}/datasets/room0__{layout}");
            let args = [
                "eval",
                "recon",
                "room0.ply",
                "--gt",
                "room0.ply",
                "--samples",
                "2000",
            ];
            ws.rslam(&[&args[..], &["--dataset", &dataset, "--json"]].concat())
                .success()
        };
        let kept = views(&format!("kept-{layout}"));
        assert!(kept.contains("\"views\""), "{kept}");
        assert_eq!(kept, views(&used), "{layout}");
        assert!(frame_files(&ws.path(&used)).is_empty(), "{layout}");
    }
}
