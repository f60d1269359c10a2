//! `runs`: many estimates against many datasets, failures by the benchmark's convention.

use std::path::Path;

use glam::{DQuat, DVec3};
use rslam_core::trajectory_io::{write_replica, write_tum, ReadOptions};
use rslam_core::{Pose, Trajectory};
use rslam_eval::runs::{evaluate_runs, write_report, RunsOptions, DEFAULT_FAILURE_ATE, NO_REASON};
use rslam_eval::EvalOptions;

fn circle(n: usize, radius: f64) -> Trajectory {
    let poses = (0..n)
        .map(|i| {
            let a = i as f64 * 0.05;
            Pose::new(
                DQuat::from_rotation_z(a),
                DVec3::new(radius * a.cos(), radius * a.sin(), 0.1 * a.sin()),
            )
        })
        .collect();
    Trajectory::from_poses_at_rate(poses, 20.0)
}

/// The ground truth with every position displaced by `offset` along z (ATE = |offset| after
/// SE(3) alignment only if the offset varies; a constant offset aligns away, so alternate it).
fn jittered(gt: &Trajectory, amplitude: f64) -> Trajectory {
    let poses = gt
        .poses
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
            Pose::new(p.rotation, p.translation + DVec3::Z * amplitude * sign)
        })
        .collect();
    Trajectory::new(gt.timestamps.clone(), poses)
}

fn mkdir(p: &Path) {
    std::fs::create_dir_all(p).unwrap();
}

/// datasets: room0 (Replica layout) and room0__fog-3 (TUM layout), office0 and office0__fog-3;
/// method "good" has all four (one as two repeats), method "bad" misses one and has one broken
/// and one with stamps that match nothing.
fn layout(root: &Path) -> RunsOptions {
    let datasets = root.join("datasets");
    let runs = root.join("runs");
    let gt = circle(100, 1.0);
    for seq in ["room0", "room0__fog-3", "office0", "office0__fog-3"] {
        let dir = datasets.join(seq);
        mkdir(&dir);
        if seq.contains("fog") {
            write_tum(&dir.join("groundtruth.txt"), &gt).unwrap();
        } else {
            write_replica(&dir.join("traj.txt"), &gt).unwrap();
        }
    }
    mkdir(&datasets.join("not_a_dataset"));

    let good = runs.join("good");
    mkdir(&good.join("office0__fog-3"));
    write_tum(&good.join("room0.txt"), &jittered(&gt, 0.001)).unwrap();
    write_tum(&good.join("office0.txt"), &jittered(&gt, 0.003)).unwrap();
    write_tum(&good.join("room0__fog-3.txt"), &jittered(&gt, 0.05)).unwrap();
    write_tum(&good.join("office0__fog-3/1.txt"), &jittered(&gt, 0.01)).unwrap();
    write_tum(&good.join("office0__fog-3/2.txt"), &jittered(&gt, 0.03)).unwrap();
    write_tum(&good.join("kitchen.txt"), &gt).unwrap();

    let bad = runs.join("bad");
    mkdir(&bad);
    write_tum(&bad.join("room0.txt"), &jittered(&gt, 0.002)).unwrap();
    std::fs::write(
        bad.join("office0.txt"),
        "0 0 0 0 0 0 0 1\n1 0 0 x 0 0 0 1\n",
    )
    .unwrap();
    let mut late = gt.clone();
    late.timestamps.iter_mut().for_each(|t| *t += 1000.0);
    write_tum(&bad.join("room0__fog-3.txt"), &late).unwrap();

    RunsOptions {
        runs_dir: runs,
        datasets_dir: datasets,
        read: ReadOptions::default(),
        eval: EvalOptions::default(),
        failure_ate: DEFAULT_FAILURE_ATE,
        skip_dir: None,
    }
}

/// Adds method "runner", laid out as a benchmark runner writes: room0 repeat 1 fine and 2 timed
/// out; room0__fog-3 failed with a stale estimate left beside its record; office0 fine (with the
/// runner's .json and .log); office0__fog-3 failed without a reason; a record of an unknown
/// sequence.
fn add_runner_records(options: &RunsOptions) {
    let gt = circle(100, 1.0);
    let runner = options.runs_dir.join("runner");
    for seq in ["room0", "room0__fog-3", "office0", "office0__fog-3"] {
        mkdir(&runner.join(seq));
    }
    let write = |path: &str, text: &str| std::fs::write(runner.join(path), text).unwrap();
    write_tum(&runner.join("room0/1.txt"), &jittered(&gt, 0.004)).unwrap();
    write("room0/2.failed", "timed out after 60 s\n");
    write_tum(&runner.join("room0__fog-3/1.txt"), &gt).unwrap();
    write(
        "room0__fog-3/1.failed",
        "estimate unreadable: <&> in line 3\n",
    );
    write_tum(&runner.join("office0/1.txt"), &jittered(&gt, 0.002)).unwrap();
    write("office0/1.json", "{\"status\": \"ok\"}");
    write("office0/1.log", "started\n");
    write("office0__fog-3/1.failed", "");
    write("garage.failed", "exit status 3\n");
}

#[test]
fn aggregates_runs_with_failures_marked() {
    let dir = tempfile::tempdir().unwrap();
    let options = layout(dir.path());
    let report = evaluate_runs(&options).unwrap();
    let s = &report.summary;
    assert_eq!(s.settings, vec!["clean", "fog-3"]);
    let names: Vec<&str> = s.methods.iter().map(|m| m.method.as_str()).collect();
    assert_eq!(names, vec!["bad", "good"]);

    // good: 5 runs (one sequence has two repeats), no failure.
    let good = &s.methods[1];
    assert_eq!((good.runs, good.failures), (5, 0));
    assert!(
        (good.cells[0].ate_mean - 0.002).abs() < 1e-6,
        "{}",
        good.cells[0].ate_mean
    );
    assert!((good.cells[1].ate_mean - (0.05 + 0.01 + 0.03) / 3.0).abs() < 1e-6);
    // Jitter leaves SR at 1 and inflates the path ratio: ±5 cm on 5 cm steps doubles the path.
    assert_eq!((good.sr.mean, good.sr.min), (Some(1.0), Some(1.0)));
    assert_eq!(good.tracked_fraction.min, Some(1.0));
    let ratio = good.cells[1].sr_path_ratio_mean.unwrap();
    assert!(ratio > 1.5, "path ratio {ratio}");

    // bad: room0 fine; office0 broken, room0__fog-3 unassociable, office0__fog-3 missing.
    let bad = &s.methods[0];
    assert_eq!((bad.runs, bad.failures), (4, 3));
    assert!((bad.cells[0].ate_mean - (0.002 + 1.0) / 2.0).abs() < 1e-6);
    assert_eq!(bad.cells[1].ate_mean, 1.0);
    // Failures count 0 for SR, path ratio and tracked fraction.
    assert_eq!(bad.cells[0].sr_mean, Some(0.5));
    assert_eq!(bad.cells[0].tracked_fraction_mean, Some(0.5));
    let fog = &bad.cells[1];
    assert_eq!(
        (
            fog.sr_mean,
            fog.sr_path_ratio_mean,
            fog.tracked_fraction_mean
        ),
        (Some(0.0), Some(0.0), Some(0.0))
    );
    assert_eq!(
        bad.csr[2].csr, 25.0,
        "failures never count as successes, even at 1 m"
    );

    let failures: Vec<&str> = report
        .runs
        .iter()
        .filter_map(|r| r.failure.as_deref())
        .collect();
    assert!(
        failures
            .iter()
            .any(|f| f.contains("office0.txt:2: field 4 'x' is not a number")),
        "{failures:?}"
    );
    assert!(
        failures
            .iter()
            .any(|f| f.contains("no matching timestamps")),
        "{failures:?}"
    );
    assert!(
        failures
            .iter()
            .any(|f| f.ends_with("office0__fog-3.txt: no estimate")),
        "{failures:?}"
    );
    assert!(report
        .unmatched
        .iter()
        .any(|p| p.ends_with("good/kitchen.txt")));

    // Survival bound: the better method per setting.
    assert!((s.survival.per_setting[0] - good.cells[0].ate_mean).abs() < 1e-12);
    assert_eq!(s.t_tests.len(), 2);
}

#[test]
fn writes_every_table() {
    let dir = tempfile::tempdir().unwrap();
    let options = layout(dir.path());
    let report = evaluate_runs(&options).unwrap();
    let out = dir.path().join("report");
    let written = write_report(&report, &out).unwrap();
    let names: Vec<String> = written
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    for expected in [
        "report.md",
        "report.json",
        "ate.csv",
        "sr.csv",
        "sr_path_ratio.csv",
        "tracked_fraction.csv",
        "csr.csv",
        "csr_curve.csv",
        "welch.csv",
        "runs.csv",
        "csr.png",
        "csr.svg",
        "report.html",
    ] {
        assert!(
            names.contains(&expected.to_string()),
            "{expected} missing from {names:?}"
        );
        assert!(std::fs::metadata(out.join(expected)).unwrap().len() > 0);
    }
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("| bad | 0.5010 (1F) | F |"), "{md}");
    assert!(md.contains("| survival upper bound |"));
    let ate_csv = std::fs::read_to_string(out.join("ate.csv")).unwrap();
    assert!(
        ate_csv.starts_with("method,clean,fog-3,mean,max\nbad,0.50099"),
        "{ate_csv}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(json["summary"]["methods"][0]["failures"], 3);
    let sr_csv = std::fs::read_to_string(out.join("sr.csv")).unwrap();
    assert!(
        sr_csv.starts_with("method,clean,fog-3,mean,min\nbad,0.5,0,0.25,0\ngood,1,1,1,1\n"),
        "{sr_csv}"
    );
    let runs_csv = std::fs::read_to_string(out.join("runs.csv")).unwrap();
    assert_eq!(runs_csv.lines().filter(|l| l.contains(",F,")).count(), 3);
    let failed = runs_csv.lines().find(|l| l.contains(",F,")).unwrap();
    assert!(
        failed.contains(",1,0,0,0,,,,"),
        "ATE 1, SR 0, ratio 0, tracked 0: {failed}"
    );
}

#[test]
fn missing_folders_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let mut options = layout(dir.path());
    options.datasets_dir = dir.path().join("runs");
    let err = evaluate_runs(&options).unwrap_err().to_string();
    assert!(err.ends_with("no dataset folder holding a ground truth; expected <datasets>/<sequence>/traj.txt (Replica), .../groundtruth.txt (TUM), .../mav0/state_groundtruth_estimate0/data.csv (EuRoC), .../mav0/mocap0/data.csv (TUM-VI) or .../metadata.yaml (a ROS 2 bag)"), "{err}");
    options.datasets_dir = dir.path().join("nope");
    assert!(evaluate_runs(&options)
        .unwrap_err()
        .to_string()
        .contains("nope"));
}

#[test]
fn failed_records_are_failed_runs_with_their_reason() {
    let dir = tempfile::tempdir().unwrap();
    let options = layout(dir.path());
    add_runner_records(&options);
    let report = evaluate_runs(&options).unwrap();
    let runner: Vec<_> = report
        .runs
        .iter()
        .filter(|r| r.method == "runner")
        .map(|r| {
            (
                r.sequence.as_str(),
                r.repeat.as_deref().unwrap(),
                r.failure.as_deref(),
            )
        })
        .collect();
    assert_eq!(
        runner,
        vec![
            ("office0", "1", None),
            ("office0__fog-3", "1", Some(NO_REASON)),
            ("room0", "1", None),
            ("room0", "2", Some("timed out after 60 s")),
            (
                "room0__fog-3",
                "1",
                Some("estimate unreadable: <&> in line 3")
            ),
        ]
    );
    let failed = report
        .runs
        .iter()
        .find(|r| r.failure.as_deref() == Some("timed out after 60 s"))
        .unwrap();
    assert_eq!(
        (failed.ate, failed.sr, failed.tracked_fraction),
        (DEFAULT_FAILURE_ATE, Some(0.0), 0.0)
    );
    let m = &report.summary.methods[2];
    assert_eq!((m.method.as_str(), m.runs, m.failures), ("runner", 5, 3));
    assert_eq!((m.cells[0].runs, m.cells[0].failures), (3, 1));
    assert!((m.cells[0].ate_mean - (0.004 + 1.0 + 0.002) / 3.0).abs() < 1e-6);
    assert_eq!((m.cells[1].failures, m.cells[1].ate_mean), (2, 1.0));
    assert!(report
        .unmatched
        .iter()
        .any(|p| p.ends_with("runner/garage.failed")));
}

#[test]
fn html_report_is_self_contained_with_tables_failures_and_figures() {
    let dir = tempfile::tempdir().unwrap();
    let options = layout(dir.path());
    add_runner_records(&options);
    let report = evaluate_runs(&options).unwrap();
    let out = dir.path().join("report");
    write_report(&report, &out).unwrap();
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    for expected in [
        "<h1>rslam eval: 3 methods × 2 settings</h1>",
        // ATE, setting rows × method columns (bad, good, runner), then the survival bound.
        "<tr><th>clean</th><td class=\"part\">0.5010 <small>1/2 F</small></td><td>0.0020</td>\
         <td class=\"part\">0.3353 <small>1/3 F</small></td><td>0.0020</td></tr>",
        "<tr><th>fog-3</th><td class=\"fail\">F <small>2/2</small></td><td>0.0300</td>\
         <td class=\"fail\">F <small>2/2</small></td><td>0.0300</td></tr>",
        // SR: a setting where every run failed is F, whatever its value.
        "<tr><th>clean</th><td class=\"part\">0.500 <small>1/2 F</small></td><td>1.000</td>",
        "<th>mean over settings</th>",
        // CSR at 1 m: runner has 2 good runs of 5.
        "<tr><th>runner</th><td>5</td><td>3</td><td>40.0 %</td><td>40.0 %</td><td>40.0 %</td></tr>",
        "<tr><th>fog</th><td>1</td><td>0.0300</td></tr>",
        "<td class=\"reason\">estimate unreadable: &lt;&amp;&gt; in line 3</td>",
        "<td class=\"reason\">failed (no reason given)</td>",
        "<th>runner</th><td>room0</td><td>2</td><td class=\"reason\">timed out after 60 s</td>",
        "<h2>Failed runs (6)</h2>",
        "<h2>Welch&#39;s t-test against clean</h2>",
        "runner/garage.failed</li>",
        "<figure id=\"bars-clean\">",
        "<figure id=\"bars-fog\">",
    ] {
        assert!(html.contains(expected), "missing {expected} in:\n{html}");
    }
    assert!(!html.contains("<&>"), "unescaped reason");
    // The CSR curve and one bar figure per category, inline.
    assert_eq!(html.matches("<svg").count(), 3);
    for external in ["src=", "href=\"http", "<script", "<link", "url(", "@import"] {
        assert!(!html.contains(external), "{external} in the HTML report");
    }
}

#[test]
fn bar_plots_are_written_per_category() {
    let dir = tempfile::tempdir().unwrap();
    let options = layout(dir.path());
    let report = evaluate_runs(&options).unwrap();
    let out = dir.path().join("report");
    let written = write_report(&report, &out).unwrap();
    for category in ["clean", "fog"] {
        for extension in ["svg", "png"] {
            let path = out.join(format!("bars/{category}.{extension}"));
            assert!(written.contains(&path), "{} not listed", path.display());
            assert!(std::fs::metadata(&path).unwrap().len() > 1000);
        }
    }
    assert_eq!(std::fs::read_dir(out.join("bars")).unwrap().count(), 4);
    let fog = std::fs::read_to_string(out.join("bars/fog.svg")).unwrap();
    // Method "bad" failed both fog-3 runs: its ATE bar carries the count.
    assert!(fog.contains("2F"), "{fog}");
    assert!(fog.contains("fog-3"));
}
