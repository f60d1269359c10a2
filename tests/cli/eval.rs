//! `rslam eval`: one pair of files, and many runs.

use crate::harness::Workspace;

/// A 30 Hz TUM trajectory on a wavy loop, every position mapped by `map` (the orientation is
/// kept: ATE and the alignment only look at positions).
pub(crate) fn tum(n: usize, t0: f64, map: impl Fn([f64; 3]) -> [f64; 3]) -> String {
    let mut text = String::from("# timestamp tx ty tz qx qy qz qw\n");
    for i in 0..n {
        let s = i as f64 / 30.0;
        let [x, y, z] = map([
            2.0 * (0.5 * s).cos(),
            1.5 * (0.5 * s).sin(),
            0.2 * (1.7 * s).sin(),
        ]);
        let half = 0.4 * s;
        text += &format!(
            "{:.6} {x:.12} {y:.12} {z:.12} 0 0 {:.12} {:.12}\n",
            t0 + s,
            half.sin(),
            half.cos()
        );
    }
    text
}

pub(crate) fn identity(p: [f64; 3]) -> [f64; 3] {
    p
}

/// Rotation by 90° about z, then a shift: an exact rigid motion.
pub(crate) fn rigid(p: [f64; 3]) -> [f64; 3] {
    [-p[1] + 5.0, p[0] - 2.0, p[2] + 1.0]
}

pub(crate) fn json_of(stdout: &str) -> serde_json::Value {
    serde_json::from_str(stdout).unwrap_or_else(|e| panic!("not JSON ({e}):\n{stdout}"))
}

#[test]
fn prints_evo_style_statistics_pairs_sr_and_alignment() {
    let ws = Workspace::new();
    ws.write("gt.txt", &tum(200, 100.0, identity));
    ws.write("est.txt", &tum(150, 100.0, rigid));
    let out = ws.rslam(&["eval", "est.txt", "gt.txt"]).success();
    for fragment in [
        "pairs\t150 of max. 150",
        "APE w.r.t. translation part (m)\n(with SE(3) Umeyama alignment)",
        "RPE w.r.t. translation part (m)\nfor delta = 1 (frames) using consecutive pairs",
        "RPE w.r.t. rotation angle in degrees (deg)",
        "      rmse\t0.000000",
        "SR (success rate of tracking)\t0.7",
        "tracked fraction\t0.750000\n  = 150 of 200 ground-truth poses",
        "SR path ratio (the paper's SR formula; grows with jitter, not a success rate)\t0.7",
        "alignment (p_gt = scale * R * p_est + t)",
        "      scale\t1.000000000",
    ] {
        assert!(out.contains(fragment), "missing '{fragment}' in:\n{out}");
    }
}

#[test]
fn json_has_the_documented_keys_and_sim3_finds_the_scale() {
    let ws = Workspace::new();
    ws.write("gt.txt", &tum(120, 0.0, identity));
    ws.write(
        "est.txt",
        &tum(120, 0.0, |p| rigid([p[0] * 0.25, p[1] * 0.25, p[2] * 0.25])),
    );
    let out = ws
        .rslam(&["eval", "est.txt", "gt.txt", "--align", "sim3", "--json"])
        .success();
    let json = json_of(&out);
    for key in ["ate", "rpe_trans", "rpe_rot_deg"] {
        for stat in ["rmse", "mean", "median", "std", "min", "max", "sse"] {
            assert!(json[key][stat].is_number(), "{key}.{stat} missing:\n{out}");
        }
    }
    assert_eq!(json["pairs"], 120);
    let scale = json["alignment"]["scale"].as_f64().unwrap();
    assert!((scale - 4.0).abs() < 1e-6, "scale {scale}");
    assert!(json["ate"]["rmse"].as_f64().unwrap() < 1e-6);
    assert_eq!(json["sr"], 1.0);
    assert_eq!(json["tracked_fraction"], 1.0);
    let path_ratio = json["sr_path_ratio"].as_f64().unwrap();
    assert!(
        (path_ratio - 1.0).abs() < 1e-6,
        "Sim(3)-scaled: {path_ratio}"
    );
    let rotation = json["alignment"]["rotation"].as_array().unwrap();
    assert_eq!(rotation.len(), 3);
    assert!(
        (rotation[0][1].as_f64().unwrap() - 1.0).abs() < 1e-6,
        "R maps est back onto gt"
    );
    assert_eq!(
        json["alignment"]["translation"].as_array().unwrap().len(),
        3
    );
}

#[test]
fn rpe_options_reach_the_library() {
    let ws = Workspace::new();
    ws.write("gt.txt", &tum(300, 0.0, identity));
    ws.write("est.txt", &tum(300, 0.0, identity));
    let consecutive = json_of(
        &ws.rslam(&["eval", "est.txt", "gt.txt", "--json", "--delta", "10"])
            .success(),
    );
    assert_eq!(consecutive["rpe_trans"]["n"], 29);
    let all = json_of(
        &ws.rslam(&[
            "eval",
            "est.txt",
            "gt.txt",
            "--json",
            "--delta",
            "10",
            "--all-pairs",
        ])
        .success(),
    );
    assert_eq!(all["rpe_trans"]["n"], 290);
    let metres = json_of(
        &ws.rslam(&[
            "eval",
            "est.txt",
            "gt.txt",
            "--json",
            "--delta",
            "1",
            "--delta-unit",
            "m",
        ])
        .success(),
    );
    assert!(metres["rpe_trans"]["n"].as_u64().unwrap() >= 1);
}

#[test]
fn t_offset_and_max_diff_control_association() {
    let ws = Workspace::new();
    ws.write("gt.txt", &tum(100, 0.0, identity));
    ws.write("est.txt", &tum(100, 50.0, identity));
    ws.rslam(&["eval", "est.txt", "gt.txt"]).fails_with(
        2,
        &[
            "no matching timestamps",
            "the estimate spans 50.000000 .. 53.300000 s, the ground truth 0.000000 .. 3.300000 s",
        ],
    );
    let out = ws
        .rslam(&["eval", "est.txt", "gt.txt", "--t-offset", "-50", "--json"])
        .success();
    assert_eq!(json_of(&out)["pairs"], 100);
}

#[test]
fn malformed_files_name_file_line_and_what_was_expected() {
    let good = "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n2 1 1 0 0 0 0 1\n";
    let cases: [(&str, &str); 7] = [
        (
            "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 1\n",
            "bad.txt:2: expected 8 numbers 't tx ty tz qx qy qz qw', found 7 fields",
        ),
        (
            "0 0 0 0 0 0 0 1\n1 1 zero 0 0 0 0 1\n",
            "bad.txt:2: field 3 'zero' is not a number",
        ),
        (
            "0 0 0 0 0 0 0 1\n1 nan 0 0 0 0 0 1\n",
            "bad.txt:2: field 2 is 'nan'; expected a finite number",
        ),
        (
            "0 0 0 0 0 0 0 1\n1 1 0 0 -inf 0 0 1\n",
            "bad.txt:2: field 5 is '-inf'; expected a finite number",
        ),
        (
            "# header\n0 0 0 0 0 0 0 0\n",
            "bad.txt:2: zero quaternion (qx qy qz qw all 0); expected a rotation",
        ),
        (
            "# only a comment\n",
            "bad.txt: no poses (the file is empty or only comments)",
        ),
        (
            "1 2 3 4 5\n",
            "bad.txt:1: cannot tell the trajectory format from 5 fields",
        ),
    ];
    let ws = Workspace::new();
    ws.write("gt.txt", good);
    for (contents, message) in cases {
        ws.write("bad.txt", contents);
        ws.rslam(&["eval", "bad.txt", "gt.txt"])
            .fails_with(2, &[message]);
    }
    ws.write("bad.txt", "1,2,3\n");
    ws.rslam(&["eval", "bad.txt", "gt.txt"]).fails_with(
        2,
        &["bad.txt:1: expected at least 8 comma-separated numbers 't[ns],px,py,pz,qw,qx,qy,qz', found 3 fields"],
    );
    ws.rslam(&["eval", "gt.txt", "gt.txt", "--format", "kitti"])
        .fails_with(
            2,
            &["gt.txt:1: expected 12 numbers (row-major 3x4 camera-to-world), found 8 fields"],
        );
    let missing = ws.rslam(&["eval", "missing.txt", "gt.txt"]);
    let message = missing.fails_with(2, &["missing.txt: No such file or directory"]);
    assert_eq!(
        message.matches("No such file").count(),
        1,
        "the cause twice: {message}"
    );
}

#[test]
fn bad_flags_and_degenerate_input_are_clear_errors() {
    let ws = Workspace::new();
    ws.write("gt.txt", &tum(50, 0.0, identity));
    ws.rslam(&["eval", "gt.txt", "gt.txt", "--align", "se2"])
        .fails_with(2, &["se2", "se3, sim3 or none"]);
    ws.rslam(&["eval", "gt.txt", "gt.txt", "--format", "csv"])
        .fails_with(
            2,
            &["expected tum, replica, kitti, euroc, colmap, ros2 or nerfstudio"],
        );
    ws.rslam(&["eval", "gt.txt", "gt.txt", "--delta", "1.5"])
        .fails_with(2, &["delta = 1.5: expected a whole number of frames >= 1"]);
    ws.rslam(&["eval", "gt.txt", "gt.txt", "--delta", "500"])
        .fails_with(2, &["try a smaller delta"]);
    ws.rslam(&["eval", "gt.txt"]).fails_with(2, &["GT"]);
    ws.write(
        "line.txt",
        "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n2 2 0 0 0 0 0 1\n",
    );
    ws.rslam(&["eval", "line.txt", "line.txt"])
        .fails_with(2, &["degenerate (they lie on a straight line)"]);
    assert!(ws
        .rslam(&["eval", "line.txt", "line.txt", "--align", "none"])
        .success()
        .contains("pairs\t3"));
}

#[test]
fn an_estimate_with_a_gap_loses_coverage_and_reports_its_tracked_fraction() {
    let ws = Workspace::new();
    let gt = tum(200, 0.0, identity);
    ws.write("gt.txt", &gt);
    // Header, then poses 0..50 and 100..200: a 50-frame gap.
    let lines: Vec<&str> = gt.lines().collect();
    let est = [&lines[..51], &lines[101..]].concat().join("\n");
    ws.write("est.txt", &est);
    let json = json_of(&ws.rslam(&["eval", "est.txt", "gt.txt", "--json"]).success());
    assert_eq!(json["tracked_fraction"], 0.75);
    assert_eq!(json["tracked_poses"], 150);
    assert_eq!(json["ground_truth_poses"], 200);
    let sr = json["sr"].as_f64().unwrap();
    let covered = json["path_length"]["covered"].as_f64().unwrap();
    let whole = json["path_length"]["ground_truth"].as_f64().unwrap();
    assert!((sr - covered / whole).abs() < 1e-12);
    // 51 of 199 segments lost, on a path whose speed varies by a few percent.
    assert!((sr - 148.0 / 199.0).abs() < 0.03, "SR {sr}");
    // The path ratio counts the straight jump across the gap as travelled.
    assert!(json["sr_path_ratio"].as_f64().unwrap() > sr);
}

#[test]
fn help_states_both_sr_definitions() {
    let ws = Workspace::new();
    let help = ws.rslam(&["eval", "--help"]).success();
    for fragment in [
        "SR (success rate of tracking) = covered ground-truth path / ground-truth path",
        "SR path ratio (sr_path_ratio) = L_est / L_gt, the paper's literal SR formula",
        "Tracked fraction = ground-truth poses with an associated estimate pose",
        "No reference tool computes these",
        "name wins, the .txt is not evaluated",
        "Writes report.html",
    ] {
        assert!(help.contains(fragment), "missing '{fragment}' in:\n{help}");
    }
}

#[test]
fn plot_writes_png_and_svg() {
    let ws = Workspace::new();
    ws.write("gt.txt", &tum(100, 0.0, identity));
    ws.write("est.txt", &tum(100, 0.0, rigid));
    for name in ["top.png", "top.svg"] {
        ws.rslam(&["eval", "est.txt", "gt.txt", "--plot", name])
            .success();
        let bytes = std::fs::read(ws.path(name)).unwrap();
        assert!(bytes.len() > 1000, "{name} is {} bytes", bytes.len());
    }
    assert_eq!(&std::fs::read(ws.path("top.png")).unwrap()[1..4], b"PNG");
    ws.rslam(&["eval", "est.txt", "gt.txt", "--plot", "top.jpg"])
        .fails_with(
            2,
            &["top.jpg: cannot draw the plot: expected a file name ending in .png or .svg"],
        );
}

#[test]
fn runs_mode_writes_the_tables_and_marks_failures() {
    let ws = Workspace::new();
    for seq in ["room0", "room0__fog-3"] {
        ws.write(
            &format!("datasets/{seq}/groundtruth.txt"),
            &tum(90, 0.0, identity),
        );
    }
    ws.write("runs/slam_a/room0.txt", &tum(90, 0.0, rigid));
    ws.write("runs/slam_a/room0__fog-3.txt", "not a trajectory\n");
    ws.write("runs/slam_b/room0.txt", &tum(90, 0.0, rigid));
    let out = ws
        .rslam(&[
            "eval",
            "--runs",
            "runs",
            "--datasets",
            "datasets",
            "--out",
            "report",
        ])
        .success();
    assert!(
        out.contains("2 methods, 2 settings, 4 runs (2 failed)"),
        "{out}"
    );
    for file in [
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
        "bars/clean.svg",
        "bars/fog.png",
    ] {
        assert!(
            ws.path(&format!("report/{file}")).is_file(),
            "{file} not written:\n{out}"
        );
    }
    let md = std::fs::read_to_string(ws.path("report/report.md")).unwrap();
    assert!(md.contains("| slam_a | 0.0000 | F |"), "{md}");
    assert!(md.contains("| slam_b | 0.0000 | F |"), "{md}");
    assert!(
        md.contains("runs/slam_b/room0__fog-3.txt: no estimate"),
        "{md}"
    );
    for section in [
        "## SR (covered fraction of the ground-truth path) per method × setting",
        "## SR path ratio (the paper's SR formula) per method × setting",
        "## Tracked fraction of frames per method × setting",
    ] {
        assert!(md.contains(section), "missing '{section}' in:\n{md}");
    }
    // Each method: clean tracked every frame, fog-3 failed.
    assert!(
        md.contains("| slam_a | 1.000 | 0.000 | 0.500 | 0.000 |"),
        "{md}"
    );
    let runs_csv = std::fs::read_to_string(ws.path("report/runs.csv")).unwrap();
    assert!(
        runs_csv.starts_with(
            "method,sequence,scene,setting,repeat,status,ate,sr,sr_path_ratio,tracked_fraction,"
        ),
        "{runs_csv}"
    );

    ws.rslam(&["eval", "--runs", "runs"])
        .fails_with(2, &["--datasets"]);
    ws.rslam(&["eval", "--runs", "runs", "--datasets", "nowhere"])
        .fails_with(2, &["nowhere"]);
}

/// A COLMAP reconstruction of the loop `tum` draws, in COLMAP's own frame (a quarter of the scale,
/// turned 90° about z, shifted), written as `images.txt` with ids in reverse name order: Sim(3)
/// alignment finds the frame again and leaves no error, as for a real SfM result.
#[test]
fn a_colmap_images_txt_is_read_as_the_cameras_it_places() {
    let ws = Workspace::new();
    ws.write("gt.txt", &tum(120, 0.0, identity));
    let mut images = String::from("# IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n");
    for i in (0..120).rev() {
        let s = i as f64 / 30.0;
        let p = [
            2.0 * (0.5 * s).cos(),
            1.5 * (0.5 * s).sin(),
            0.2 * (1.7 * s).sin(),
        ];
        // Camera-to-world in COLMAP's frame: a turn of θ about z, centre 0.25 R₀ p + (5, −2, 1).
        let theta = 0.8 * s + std::f64::consts::FRAC_PI_2;
        let c = [0.25 * -p[1] + 5.0, 0.25 * p[0] - 2.0, 0.25 * p[2] + 1.0];
        // World-to-camera: the turn by −θ, and t = −R(−θ) c.
        let (sin, cos) = theta.sin_cos();
        let t = [
            -(c[0] * cos + c[1] * sin),
            -(-c[0] * sin + c[1] * cos),
            -c[2],
        ];
        let (qz, qw) = ((-theta / 2.0).sin(), (-theta / 2.0).cos());
        images += &format!(
            "{} {qw:.15} 0 0 {qz:.15} {:.15} {:.15} {:.15} 1 frame_{i:05}.png\n\n",
            120 - i,
            t[0],
            t[1],
            t[2]
        );
    }
    ws.write("images.txt", &images);
    let out = ws
        .rslam(&[
            "eval",
            "images.txt",
            "gt.txt",
            "--align",
            "sim3",
            "--rate",
            "30",
            "--json",
        ])
        .success();
    let json = json_of(&out);
    assert_eq!(json["pairs"], 120);
    assert!(json["ate"]["rmse"].as_f64().unwrap() < 1e-6, "{out}");
    assert!(json["rpe_rot_deg"]["max"].as_f64().unwrap() < 1e-6, "{out}");
    let scale = json["alignment"]["scale"].as_f64().unwrap();
    assert!((scale - 4.0).abs() < 1e-6, "scale {scale}");
}
