//! Runs that stop part-way and go on: SIGKILL mid-render then the same command gives the bytes
//! of an uninterrupted run; another job on that folder is refused; `--force` starts over;
//! `rslam verify` catches a changed file.

use std::time::Duration;

use crate::dataset_check::{assert_same_tree, files, tree};
use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

const FRAMES: &str = "300";

fn render_args(format: &str) -> Vec<&str> {
    vec![
        "render",
        "--scene",
        "room0",
        "--frames",
        FRAMES,
        "--camera",
        SMALL_CAMERA,
        "--format",
        format,
        "--perturb",
        // auto_exposure carries its controller from frame to frame: a resumed run must give
        // the frames after the kill what the frames before them left.
        "gaussian_noise:3@dynamic,auto_exposure:2,depth_missing:2,misalign:3@dynamic",
        "--seed",
        "5",
        "--out",
        "ds",
    ]
}

/// Starts `rslam ARGS` in `ws` and SIGKILLs it once the dataset `out` holds more than 40 files
/// starting with `prefix` in its folder `watch`.
pub fn kill_mid_run(ws: &Workspace, args: &[&str], out: &str, watch: &str, prefix: &str) {
    let mut child = ws.spawn_rslam(args);
    let watched = ws.path(out).join(watch);
    for _ in 0..1200 {
        if watched.is_dir() && files(&watched, prefix).len() > 40 {
            break;
        }
        std::thread::sleep(Duration::from_millis(25));
    }
    child.kill().unwrap(); // SIGKILL: no handler runs, nothing is tidied up
    child.wait().unwrap();
    let written = files(&watched, prefix).len();
    assert!(
        written > 40 && !ws.path(out).join("rslam.json").exists(),
        "the run was not killed mid-way ({written} files); raise FRAMES"
    );
    assert!(
        ws.path(out).join("rslam.run.json").exists(),
        "a killed run is marked unfinished"
    );
}

#[test]
fn a_killed_render_resumes_to_the_bytes_of_an_uninterrupted_one() {
    for (format, watch, prefix) in [("replica", "results", "frame"), ("tum", "rgb", "")] {
        let whole = Workspace::new();
        whole.rslam(&render_args(format)).success();
        let killed = Workspace::new();
        kill_mid_run(&killed, &render_args(format), "ds", watch, prefix);
        let resumed = killed.rslam(&render_args(format));
        resumed.success();
        assert!(resumed.stderr().contains("resumed"), "{}", resumed.stderr());
        let again = killed.rslam(&render_args(format));
        again.success();
        assert!(
            again.stderr().contains("already complete"),
            "{}",
            again.stderr()
        );
        assert_same_tree(&whole.path("ds"), &killed.path("ds"));
        assert!(!killed.path("ds/rslam.run.json").exists());
    }
}

#[test]
fn another_job_is_refused_and_force_starts_over() {
    let ws = Workspace::new();
    let small = [
        "--scene",
        "room0",
        "--frames",
        "4",
        "--camera",
        SMALL_CAMERA,
        "--out",
        "ds",
    ];
    let run = |extra: &[&str]| ws.rslam(&[&["render"][..], &small, extra].concat());
    run(&["--seed", "1"]).success();
    let before = tree(&ws.path("ds"));
    run(&["--seed", "2"]).fails_with(
        2,
        &["ds", "another job", "seed 1", "differs in seed", "--force"],
    );
    assert_eq!(
        tree(&ws.path("ds")),
        before,
        "a refused run changes nothing"
    );
    run(&["--seed", "2", "--force"]).success();
    assert_eq!(crate::dataset_check::manifest(&ws.path("ds")).seed, 2);

    ws.write("mine/notes.txt", "not rslam's");
    ws.rslam(&[&["render"][..], &small[..6], &["--out", "mine", "--force"]].concat())
        .fails_with(2, &["mine", "holds no rslam output"]);
    assert!(
        ws.path("mine/notes.txt").exists(),
        "--force never deletes other files"
    );

    ws.rslam(&[
        "perturb",
        "--input",
        "ds",
        "--out",
        "./ds",
        "--perturb",
        "fog:1",
        "--force",
    ])
    .fails_with(2, &["ds", "is the input itself"]);
    assert_eq!(
        crate::dataset_check::manifest(&ws.path("ds")).seed,
        2,
        "input untouched"
    );
}

#[test]
fn verify_accepts_a_fresh_dataset_and_names_a_changed_or_missing_file() {
    let ws = Workspace::new();
    ws.rslam(&[
        "render",
        "--scene",
        "room0",
        "--frames",
        "3",
        "--camera",
        SMALL_CAMERA,
        "--format",
        "tum",
        "--out",
        "ds",
    ])
    .success();
    let ok = ws.rslam(&["verify", "ds"]).success();
    assert!(ok.contains("ok"), "{ok}");
    let depth = files(&ws.path("ds/depth"), "")[1].clone();
    let mut bytes = std::fs::read(&depth).unwrap();
    let last = bytes.len() - 20;
    bytes[last] ^= 1;
    std::fs::write(&depth, bytes).unwrap();
    std::fs::remove_file(ws.path("ds/groundtruth.txt")).unwrap();
    let run = ws.rslam(&["verify", "ds"]);
    assert_eq!(run.output.status.code(), Some(1));
    let out = run.stdout();
    let name = depth
        .strip_prefix(ws.path("ds"))
        .unwrap()
        .display()
        .to_string();
    assert!(out.contains(&format!("{name}: content changed")), "{out}");
    assert!(out.contains("groundtruth.txt: missing"), "{out}");
    ws.rslam(&["verify", "nothing"])
        .fails_with(2, &["nothing", "rslam.json"]);
}
