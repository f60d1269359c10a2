//! `rslam suite bench` and `report` with stand-in methods: one that returns the ground truth,
//! one that crashes, one that hangs past its timeout, one that writes garbage. Each failure is
//! recorded with its reason and reported as F; finished runs are never run again.

use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

fn suite(ws: &Workspace) {
    ws.write(
        "suite/suite.toml",
        &format!(
            "[defaults]\nframes = 6\nformat = \"tum\"\ncamera = \"{SMALL_CAMERA}\"\n\
             [[sequence]]\nname = \"room0__clean\"\nscene = \"room0\"\n\
             [[sequence]]\nname = \"room0__fog-3\"\nscene = \"room0\"\nperturb = \"fog:3\"\n"
        ),
    );
    ws.rslam(&["suite", "run", "suite"]).success();
}

fn method(ws: &Workspace, name: &str, command: &str, timeout_s: f64, repeats: usize) -> String {
    let path = format!("methods/{name}.toml");
    ws.write(
        &path,
        &format!("name = \"{name}\"\nreads = \"tum\"\ncommand = {command}\ntimeout_s = {timeout_s}\nrepeats = {repeats}\n"),
    );
    path
}

fn report_runs(ws: &Workspace) -> Vec<serde_json::Value> {
    let text = std::fs::read_to_string(ws.path("suite/report/report.json")).unwrap();
    let report: serde_json::Value = serde_json::from_str(&text).unwrap();
    report["runs"].as_array().unwrap().clone()
}

#[test]
fn failures_are_recorded_with_their_reason_and_finished_runs_are_kept() {
    let ws = Workspace::new();
    suite(&ws);
    let methods = [
        method(
            &ws,
            "oracle",
            r#"["cp", "{dataset}/groundtruth.txt", "{estimate}"]"#,
            30.0,
            2,
        ),
        method(
            &ws,
            "crash",
            r#"["sh", "-c", "echo dying >&2; exit 3"]"#,
            30.0,
            1,
        ),
        method(&ws, "hang", r#"["sleep", "30"]"#, 0.5, 1),
        method(
            &ws,
            "garbage",
            r#"["sh", "-c", "echo not a trajectory > \"$1\"", "sh", "{estimate}"]"#,
            30.0,
            1,
        ),
    ];
    let mut args = vec!["suite", "bench", "suite"];
    for m in &methods {
        args.extend(["--methods", m.as_str()]);
    }
    let first = ws.rslam(&args);
    first.success();
    assert!(
        first
            .stderr()
            .contains("4 runs succeeded, 6 failed now; 0 were done before"),
        "{}",
        first.stderr()
    );
    let run =
        |m: &str, s: &str, r: usize, ext: &str| ws.path(&format!("suite/runs/{m}/{s}/{r}.{ext}"));
    assert!(run("oracle", "room0__fog-3", 1, "txt").is_file());
    let crash = std::fs::read_to_string(run("crash", "room0__clean", 0, "failed")).unwrap();
    assert!(crash.starts_with("exit status 3"), "{crash}");
    assert!(
        std::fs::read_to_string(run("crash", "room0__clean", 0, "log"))
            .unwrap()
            .contains("dying")
    );
    let hang = std::fs::read_to_string(run("hang", "room0__clean", 0, "failed")).unwrap();
    assert!(hang.starts_with("timed out after 0.5 s"), "{hang}");
    let garbage = std::fs::read_to_string(run("garbage", "room0__clean", 0, "failed")).unwrap();
    assert!(garbage.starts_with("estimate unreadable"), "{garbage}");
    assert!(
        !run("garbage", "room0__clean", 0, "txt").exists(),
        "a failed estimate is not left for eval"
    );
    let record: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(run("oracle", "room0__clean", 0, "json")).unwrap(),
    )
    .unwrap();
    assert_eq!(record["exit_code"], 0);
    assert!(record["seconds"].as_f64().unwrap() > 0.0 && record["peak_rss_mb"].as_f64().is_some());
    assert!(
        !ws.path("suite/runs/oracle/room0__clean/0.work").exists(),
        "scratch folders go"
    );

    let again = ws.rslam(&args);
    assert!(
        again
            .stderr()
            .contains("0 runs succeeded, 0 failed now; 10 were done before"),
        "{}",
        again.stderr()
    );
    let retry = ws.rslam(&[&args[..], &["--retry-failed"]].concat());
    assert!(
        retry
            .stderr()
            .contains("0 runs succeeded, 6 failed now; 4 were done before"),
        "{}",
        retry.stderr()
    );

    ws.rslam(&["suite", "report", "suite"]).success();
    let runs = report_runs(&ws);
    assert_eq!(runs.len(), 10);
    for r in &runs {
        let (method, failure) = (r["method"].as_str().unwrap(), r["failure"].as_str());
        match method {
            "oracle" => assert!(
                failure.is_none() && r["ate"].as_f64().unwrap() < 1e-6,
                "{r}"
            ),
            "crash" => assert!(failure.unwrap().starts_with("exit status 3"), "{r}"),
            "hang" => assert!(failure.unwrap().starts_with("timed out"), "{r}"),
            _ => assert!(failure.unwrap().starts_with("estimate unreadable"), "{r}"),
        }
        if failure.is_some() {
            assert_eq!(r["ate"].as_f64(), Some(1.0), "the failure convention");
        }
    }
}

#[test]
fn a_method_for_another_layout_is_refused_before_any_run() {
    let ws = Workspace::new();
    suite(&ws);
    ws.write(
        "m.toml",
        "name = \"nice\"\nreads = \"replica\"\ncommand = [\"true\"]\ntimeout_s = 5\n",
    );
    ws.rslam(&["suite", "bench", "suite", "--methods", "m.toml"])
        .fails_with(
            2,
            &[
                "method 'nice' reads the replica layout",
                "2 sequence(s)",
                "--format replica",
            ],
        );
    assert!(!ws.path("suite/runs").exists());
    ws.write(
        "bad.toml",
        "name = \"x\"\nreads = \"tum\"\ncommand = [\"{dataset\"]\ntimeout_s = 5\n",
    );
    ws.rslam(&["suite", "bench", "suite", "--methods", "bad.toml"])
        .fails_with(2, &["bad.toml:3:", "a lone '{'"]);
}

/// A method file `<name>.toml` whose run copies the ground truth as its estimate, then runs the
/// shell `script` with `$1` the dataset, `$3` `{work}/<file>`, which the file declares as `key`.
fn oracle_writing(ws: &Workspace, name: &str, (key, file): (&str, &str), script: &str) {
    ws.write(
        &format!("{name}.toml"),
        &format!(
            r#"name = "{name}"
reads = "tum"
timeout_s = 30
{key} = "{{work}}/{file}"
command = ["sh", "-c", "cp \"$1/groundtruth.txt\" \"$2\" && {script}", "sh", "{{dataset}}", "{{estimate}}", "{{work}}/{file}"]
"#
        ),
    );
}

/// Two mappers: one writes the scene's own mesh, one a triangle no camera of the sequence saw.
/// Culled to what the cameras saw (the default), the first is perfect over a part of the room
/// and the second is reported as not measured; without culling, both are measured over the whole
/// room.
#[test]
fn a_reconstruction_is_kept_and_measured_against_what_the_cameras_saw() {
    let ws = Workspace::new();
    suite(&ws);
    ws.rslam(&["scene", "export", "room0", "--out", "room0.ply"])
        .success();
    let mapper = |name: &str, writes: &str| {
        oracle_writing(
            &ws,
            name,
            ("mesh", "mesh.ply"),
            &format!(r#"{writes} > \"$3\""#),
        );
    };
    mapper(
        "scene_mesh",
        &format!("cat '{}'", ws.path("room0.ply").display()),
    );
    mapper(
        "far_triangle",
        r"printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 10\n1 0 10\n0 1 10\n3 0 1 2\n'",
    );
    ws.rslam(&[
        "suite",
        "bench",
        "suite",
        "--methods",
        "scene_mesh.toml",
        "--methods",
        "far_triangle.toml",
    ])
    .success();
    assert!(ws
        .path("suite/runs/far_triangle/room0__fog-3/0.mesh.ply")
        .is_file());

    let out = ws.rslam(&["suite", "report", "suite"]).success();
    assert!(
        out.contains("4 reconstruction(s) against the ground-truth meshes, culling visible"),
        "{out}"
    );
    assert!(
        out.contains("far_triangle room0__clean #0: not measured: "),
        "{out}"
    );
    assert!(ws.path("suite/report/ground_truth/room0.ply").is_file());
    let rows = |ws: &Workspace| -> Vec<Vec<String>> {
        let csv = std::fs::read_to_string(ws.path("suite/report/reconstruction.csv")).unwrap();
        assert!(csv.starts_with("method,sequence,repeat,accuracy_cm,completion_cm,completion_ratio_percent,culling,reconstruction_kept_percent,ground_truth_kept_percent,failure\n"), "{csv}");
        csv.lines()
            .skip(1)
            .map(|l| l.splitn(10, ',').map(String::from).collect())
            .collect()
    };
    let number = |v: &String| v.parse::<f64>().unwrap();
    for row in rows(&ws) {
        if row[0] == "scene_mesh" {
            assert_eq!(
                (number(&row[3]), number(&row[4]), number(&row[5])),
                (0.0, 0.0, 100.0),
                "{row:?}"
            );
            assert_eq!(row[6], "visible");
            assert!(
                number(&row[8]) < 50.0,
                "6 frames see part of the room: {row:?}"
            );
        } else {
            assert!(
                row[3].is_empty()
                    && row[9].contains("no point of it lies in what the ground-truth cameras saw"),
                "{row:?}"
            );
        }
    }

    ws.rslam(&["suite", "report", "suite", "--cull", "none"])
        .success();
    for row in rows(&ws) {
        assert_eq!(row[6], "none", "{row:?}");
        assert_eq!(number(&row[8]), 100.0);
        if row[0] == "far_triangle" {
            // One triangle far from most of the room, covering almost none of it.
            assert!(
                number(&row[3]) > 1.0 && number(&row[4]) > 10.0 && number(&row[5]) < 10.0,
                "{row:?}"
            );
        }
    }
}

/// A "renderer" that hands back the dataset's own frames as its map's views: on the clean
/// sequence they are the clean frames (PSNR infinite, SSIM 1, depth L1 0); under fog, colour
/// differs and depth does not. One named like no frame is reported, not fatal.
#[test]
fn rendered_views_are_measured_against_the_clean_frames_of_the_same_job() {
    let ws = Workspace::new();
    suite(&ws);
    let renderer = |name: &str, copy: &str| {
        oracle_writing(
            &ws,
            name,
            ("renders", "renders"),
            &format!(r#"mkdir \"$3\" && {copy}"#),
        );
    };
    renderer("copies_frames", r#"cp -r \"$1/rgb\" \"$1/depth\" \"$3/\""#);
    renderer(
        "misnames",
        r#"cp \"$(ls \"$1\"/rgb/*.png | head -1)\" \"$3/frame.png\""#,
    );
    ws.rslam(&[
        "suite",
        "bench",
        "suite",
        "--methods",
        "copies_frames.toml",
        "--methods",
        "misnames.toml",
    ])
    .success();
    let out = ws.rslam(&["suite", "report", "suite"]).success();
    assert!(
        out.contains("4 run(s) rendered their map at the ground-truth poses"),
        "{out}"
    );
    assert!(out.contains("copies_frames room0__clean #0: PSNR inf dB, SSIM 1.0000 over 6 frame(s); depth L1 0.00 cm over 6"), "{out}");
    assert!(
        out.contains("misnames room0__fog-3 #0: not measured: ")
            && out.contains(
                "frame.png: named like no frame of the dataset (expected e.g. rgb/0.000000.png)"
            ),
        "{out}"
    );
    assert!(out.contains("psnr_db against ATE over "), "{out}");
    assert!(ws
        .path("suite/report/clean/room0__fog-3/rslam.json")
        .is_file());

    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(ws.path("suite/report/rendered_views.json")).unwrap(),
    )
    .unwrap();
    let row = |method: &str, sequence: &str| {
        json.as_array()
            .unwrap()
            .iter()
            .find(|r| r["method"] == method && r["sequence"] == sequence)
            .unwrap()
            .clone()
    };
    let fog = &row("copies_frames", "room0__fog-3")["quality"];
    let psnr = fog["psnr_db"].as_f64().unwrap();
    let ssim = fog["ssim"].as_f64().unwrap();
    assert!(
        psnr > 5.0 && psnr < 30.0 && ssim < 0.99,
        "fog changes colour: {fog}"
    );
    assert_eq!(fog["depth_l1_cm"], 0.0, "and not depth: {fog}");
    assert_eq!(
        row("copies_frames", "room0__clean")["quality"]["psnr_db"],
        serde_json::Value::Null
    );
    // The clean frames are made once, then found complete.
    let manifest = ws.path("suite/report/clean/room0__fog-3/rslam.json");
    let made = std::fs::metadata(&manifest).unwrap().modified().unwrap();
    let again = ws.rslam(&["suite", "report", "suite"]).success();
    let measured = again
        .lines()
        .filter(|l| l.starts_with("copies_frames room0__"));
    assert_eq!(measured.count(), 2, "{again}");
    assert_eq!(
        std::fs::metadata(&manifest).unwrap().modified().unwrap(),
        made
    );
}

/// A rig row is made in the EuRoC layout; a method that reads it gets the dataset and ORB-SLAM3's
/// stereo settings as `{camera}`, and the report scores it against the body's ground truth.
#[test]
fn a_euroc_method_gets_the_rig_dataset_and_its_stereo_settings() {
    let ws = Workspace::new();
    ws.write(
        "suite/suite.toml",
        "[[sequence]]\nname = \"room0__stereo\"\nscene = \"room0\"\nframes = 6\n\
         format = \"euroc\"\nrig = \"stereo-imu\"\n",
    );
    ws.rslam(&["suite", "run", "suite"]).success();
    // Checks what it is given, then answers with the ground truth (ns, p, q w-first) as TUM.
    let check_and_copy = r#"test "$2" = "$1/orbslam3_stereo.yaml" && grep -q Stereo.T_c1_c2 "$2" && test -s "$1/mav0/cam1/data.csv" && awk -F, '!/^#/ {{ printf "%.9f %s %s %s %s %s %s %s\n", $1 / 1e9, $2, $3, $4, $6, $7, $8, $5 }}' "$1/mav0/state_groundtruth_estimate0/data.csv" > "$3" && mkdir "$4""#;
    ws.write(
        "oracle.toml",
        &format!(
            "name = \"oracle\"\nreads = \"euroc\"\ncommand = [\"sh\", \"-c\", '''{check_and_copy}''', \"sh\", \"{{dataset}}\", \"{{camera}}\", \"{{estimate}}\", \"{{work}}/renders\"]\ntimeout_s = 30\nrenders = \"{{work}}/renders\"\n"
        ),
    );
    ws.write(
        "replica.toml",
        "name = \"vo\"\nreads = \"replica\"\ncommand = [\"true\"]\ntimeout_s = 5\n",
    );
    ws.rslam(&["suite", "bench", "suite", "--methods", "replica.toml"])
        .fails_with(
            2,
            &[
                "method 'vo' reads the replica layout but 1 sequence(s) of the suite are euroc",
                "`rslam suite init --format replica`",
            ],
        );
    let bench = ws.rslam(&["suite", "bench", "suite", "--methods", "oracle.toml"]);
    bench.success();
    assert!(
        bench
            .stderr()
            .contains("1 runs succeeded, 0 failed now; 0 were done before"),
        "{}",
        bench.stderr()
    );
    // Its (empty) renders are not compared on a rig's sequence: a row says so, the report goes on.
    let report = ws.rslam(&["suite", "report", "suite"]).success();
    assert!(
        report.contains("oracle room0__stereo #0: not measured: room0__stereo: rendered views are compared in the replica and tum layouts, not euroc"),
        "{report}"
    );
    let runs = report_runs(&ws);
    assert_eq!(runs.len(), 1);
    assert!(
        runs[0]["failure"].is_null() && runs[0]["ate"].as_f64().unwrap() < 1e-6,
        "{}",
        runs[0]
    );
}
