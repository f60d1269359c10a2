//! Golden outputs: a table of commands covering every layout (Replica, TUM, EuRoC, image folder,
//! one image), every rig preset and a rig file, `--agents`, a mesh along a trajectory file,
//! recorded-dataset perturbs (rslam's own TUM and EuRoC outputs, a TUM folder without a manifest,
//! a TUM-VI export), image, depth, motion, stream, sensor, lens, IMU and calibration items,
//! `@dynamic`, `misalign`, `fast` and a resumed run — each with the BLAKE3 digest of every file it
//! writes (`rslam.json` with its `tool_version` masked).
//!
//! The digests in `golden/digests.txt` were recorded on lavapipe (every command here asks for
//! `--adapter llvmpipe`; a GPU rounds floats differently); the file names the adapter they belong
//! to, and the test refuses to compare against another. Changes of shape keep every digest. A
//! deliberate change to bytes is a commit of its own that records the table again and says why:
//! `RSLAM_GOLDEN=record cargo test -p rslam-cli --test cli golden`.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use crate::dataset_check::tree;
use crate::harness::Workspace;

const DIGESTS: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../tests/cli/golden/digests.txt"
);
const CAMERA: &str = "96,64,60,60,47.5,31.5";
const ADAPTER: &str = "llvmpipe";
const LENS: &str = "distortion:radtan(-0.2,0.05,0.001,-0.002)";
const VERSION_FIELD: &str = concat!("\"tool_version\": \"", env!("CARGO_PKG_VERSION"), "\"");

/// Two small grey cameras 0.1 m apart, the second on a clock 1.5 ms ahead, and a 100 Hz IMU.
const RIG_FILE: &str = r#"name = "tiny"

[[camera]]
T_BS = [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]
rate_hz = 20
resolution = [96, 64]
intrinsics = [60, 60, 47.5, 31.5]

[[camera]]
T_BS = [1, 0, 0, 0.1,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]
rate_hz = 20
resolution = [96, 64]
intrinsics = [60, 60, 47.5, 31.5]
colour = "rgb"
time_offset_ms = 1.5

[imu]
rate_hz = 100
gyroscope_noise_density = 1.6968e-4
gyroscope_random_walk = 1.9393e-5
accelerometer_noise_density = 2.0e-3
accelerometer_random_walk = 3.0e-3
"#;

/// A closed box room, 4 × 3 × 2.5 m, faces inward, for the mesh source.
const BOX_OBJ: &str = "v -2 0 -1.5\nv 2 0 -1.5\nv 2 0 1.5\nv -2 0 1.5\nv -2 2.5 -1.5\nv 2 2.5 -1.5\nv 2 2.5 1.5\nv -2 2.5 1.5\n\
f 1 2 3\nf 1 3 4\nf 5 7 6\nf 5 8 7\nf 1 5 6\nf 1 6 2\nf 2 6 7\nf 2 7 3\nf 3 7 8\nf 3 8 4\nf 4 8 5\nf 4 5 1\n";

/// A TUM trajectory inside the box: timestamp tx ty tz qx qy qz qw.
fn box_path() -> String {
    (0..6)
        .map(|i| {
            let s = i as f64 * 0.1;
            let half = 0.1 * s;
            format!(
                "{:.4} {:.4} 1.2 {:.4} 0 {:.6} 0 {:.6}\n",
                s,
                -0.5 + s,
                0.2 * s,
                half.sin(),
                half.cos()
            )
        })
        .collect()
}

/// One step of the table: what it is called, what it runs, what it writes.
struct Case {
    name: &'static str,
    args: Vec<String>,
    /// The folder (or, for one image, the file) whose every file is digested.
    out: &'static str,
    /// Run before the command, in the workspace.
    before: Option<fn(&Workspace)>,
    /// A fragment the command's stderr must hold.
    says: Option<&'static str>,
}

fn render(out: &'static str, args: &[&str]) -> Case {
    let mut all = vec!["render", "--scene", "room0", "--out", out];
    all.extend(args);
    case(out, out, &all)
}

fn perturb(out: &'static str, input: &str, spec: &str) -> Case {
    case(
        out,
        out,
        &["perturb", "--input", input, "--perturb", spec, "--out", out],
    )
}

fn case(name: &'static str, out: &'static str, args: &[&str]) -> Case {
    let mut args: Vec<String> = args.iter().map(|a| a.to_string()).collect();
    args.extend(["--adapter".to_string(), ADAPTER.to_string()]);
    Case {
        name,
        args,
        out,
        before: None,
        says: None,
    }
}

fn table() -> Vec<Case> {
    let small = ["--camera", CAMERA, "--frames"];
    let resumable = [
        "--format",
        "tum",
        "--camera",
        CAMERA,
        "--frames",
        "8",
        "--seed",
        "9",
        "--perturb",
        "auto_exposure:2,gaussian_noise:2@dynamic,misalign:2",
    ];
    vec![
        render("replica", &[&small[..], &["4"]].concat()),
        render(
            "replica_image",
            &[
                &small[..],
                &["4", "--seed", "3", "--perturb"],
                &["gaussian_noise:3,fog:2,motion_blur:2,jpeg_compression:4,frost:1,spatter:2"],
            ]
            .concat(),
        ),
        render(
            "tum_depth",
            &[
                &small[..],
                &["4", "--format", "tum", "--perturb"],
                &["depth_noise:3,depth_missing:2,depth_edge_erosion:2,depth_noise_kinect:1,depth_range:4"],
            ]
            .concat(),
        ),
        render(
            "tum_depth_sensor",
            &[
                &small[..],
                &["3", "--format", "tum", "--depth-png", "small", "--perturb"],
                &["depth_sensor:3,vignetting:3"],
            ]
            .concat(),
        ),
        render(
            "tum_motion",
            &[
                &small[..],
                &["10", "--format", "tum", "--perturb", "rot:1,trans:0.0125@smooth,fast:2"],
            ]
            .concat(),
        ),
        render(
            "tum_dynamic",
            &[
                &small[..],
                &["8", "--format", "tum", "--seed", "5", "--perturb"],
                &["gaussian_noise:3@dynamic,depth_missing:3@dynamic,misalign:2@dynamic"],
            ]
            .concat(),
        ),
        render(
            "ros2",
            &[
                &small[..],
                &["5", "--format", "ros2", "--perturb", "motion_blur:2"],
            ]
            .concat(),
        ),
        perturb("ros2_perturbed", "ros2", "gaussian_noise:2,depth_missing:2"),
        render(
            "ros2_rgbd_imu",
            &[&small[..], &["6", "--rig", "rgbd-imu", "--format", "ros2"]].concat(),
        ),
        render(
            "ros2_stereo_imu",
            &[
                "--frames",
                "6",
                "--rig",
                "stereo-imu",
                "--format",
                "ros2",
                "--perturb",
                "cam1:fog:3,imu_noise:2",
            ],
        ),
        render(
            "replica_sensor",
            &[&small[..], &["3", "--perturb", "exposure:20,rolling_shutter:10"]].concat(),
        ),
        render(
            "replica_lens",
            &[&small[..], &["3", "--perturb", LENS]].concat(),
        ),
        render(
            "rig_rgbd",
            &[&small[..], &["3", "--rig", "rgbd", "--perturb", "contrast:3"]].concat(),
        ),
        render(
            "rig_rgbd_imu",
            &[
                &small[..],
                &["6", "--rig", "rgbd-imu", "--format", "tum", "--perturb"],
                &["imu_noise:3,gaussian_noise:1"],
            ]
            .concat(),
        ),
        render(
            "rig_stereo",
            &[
                "--frames",
                "5",
                "--rig",
                "stereo",
                "--format",
                "euroc",
                "--perturb",
                "cam1:fog:3,baseline:0.01,cam0:extrinsic_rot:1@dynamic",
            ],
        ),
        render(
            "rig_stereo_imu",
            &[
                "--frames",
                "10",
                "--rig",
                "stereo-imu",
                "--format",
                "euroc",
                "--perturb",
                "imu_bias_step:0.02/0.3,cam_imu_offset:2.5,fast:2,gaussian_noise:2",
            ],
        ),
        Case {
            before: Some(|ws| {
                ws.write("tiny.toml", RIG_FILE);
            }),
            ..render(
                "rig_file",
                &[
                    "--frames",
                    "6",
                    "--rig",
                    "tiny.toml",
                    "--format",
                    "euroc",
                    "--perturb",
                    &format!("imu0:extrinsic_rot:2,{LENS},cam1:motion_blur:2"),
                ],
            )
        },
        render(
            "rig_calibration",
            &[
                "--frames",
                "5",
                "--rig",
                "tiny.toml",
                "--format",
                "euroc",
                "--perturb",
                "baseline:0.01@calibration,cam1:extrinsic_trans:0.005@calibration,imu_noise:2",
            ],
        ),
        render(
            "agents",
            &[&small[..], &["4", "--format", "tum", "--agents", "2"]].concat(),
        ),
        Case {
            before: Some(|ws| {
                ws.write("box.obj", BOX_OBJ);
                ws.write("box_path.txt", &box_path());
            }),
            ..case(
                "mesh",
                "mesh",
                &[
                    "render",
                    "--scene",
                    "box.obj",
                    "--traj",
                    "box_path.txt",
                    "--camera",
                    CAMERA,
                    "--format",
                    "tum",
                    "--perturb",
                    "shot_noise:2",
                    "--out",
                    "mesh",
                ],
            )
        },
        perturb(
            "p_replica",
            "replica",
            "contrast:3,gaussian_blur:2,defocus_blur:2,glass_blur:1,brightness:3,impulse_noise:2,depth_noise:2",
        ),
        perturb(
            "p_tum",
            "tum_depth",
            "gaussian_noise:2@dynamic,misalign:1,fast:2,zoom_blur:1",
        ),
        Case {
            before: Some(|ws| {
                copy_tree(&ws.path("tum_depth"), &ws.path("foreign_tum"));
                for own in ["rslam.json", "rslam.b3sum"] {
                    std::fs::remove_file(ws.path("foreign_tum").join(own)).unwrap();
                }
            }),
            ..case(
                "p_foreign_tum",
                "p_foreign_tum",
                &[
                    "perturb",
                    "--input",
                    "foreign_tum",
                    "--camera",
                    CAMERA,
                    "--perturb",
                    "speckle_noise:2,depth_missing:1",
                    "--out",
                    "p_foreign_tum",
                ],
            )
        },
        perturb(
            "p_rgbd_imu",
            "rig_rgbd_imu",
            "imu_noise:2,speckle_noise:2",
        ),
        perturb(
            "p_euroc",
            "rig_stereo_imu",
            "cam1:gaussian_noise:3,saturate:2,imu_noise:2,cam_imu_offset:1",
        ),
        perturb(
            "p_euroc_calibration",
            "rig_stereo_imu",
            "baseline:0.01@calibration,imu0:extrinsic_rot:1@calibration",
        ),
        Case {
            before: Some(|ws| crate::perturb_tumvi::write_tum_vi_style(&ws.path("tumvi"), false)),
            ..perturb("p_tumvi", "tumvi", "gaussian_noise:3,cam1:fog:2")
        },
        perturb(
            "p_tumvi_imu",
            "tumvi",
            "imu_noise:3,baseline:0.01@calibration",
        ),
        Case {
            before: Some(|ws| {
                let images = ws.path("images");
                std::fs::create_dir_all(&images).unwrap();
                for frame in ["frame000000.jpg", "frame000001.jpg"] {
                    std::fs::copy(ws.path("replica/results").join(frame), images.join(frame))
                        .unwrap();
                }
                let tum_rgb = first_file(&ws.path("tum_depth/rgb"));
                std::fs::copy(tum_rgb, images.join("tum.png")).unwrap();
            }),
            ..perturb(
                "p_images",
                "images",
                "snow:2,spatter:3,elastic_transform:2",
            )
        },
        case(
            "p_one_image",
            "one.jpg",
            &[
                "perturb",
                "--input",
                "images/frame000001.jpg",
                "--perturb",
                "pixelate:3,saturate:4,impulse_noise:1",
                "--out",
                "one.jpg",
            ],
        ),
        render("resumed_first", &resumable),
        Case {
            before: Some(|ws| {
                // What a run stopped part-way leaves: frames missing, a file cut off mid-write.
                let root = ws.path("resumed_first");
                let mut rgb: Vec<_> = tree(&root.join("rgb")).into_keys().collect();
                rgb.sort();
                for name in &rgb[rgb.len() - 3..] {
                    std::fs::remove_file(root.join("rgb").join(name)).unwrap();
                }
                std::fs::write(root.join("rgb/cut.png.partial"), b"half a frame").unwrap();
                copy_tree(&root, &ws.path("resumed"));
            }),
            says: Some("resumed"),
            ..render("resumed", &resumable)
        },
    ]
}

fn first_file(dir: &Path) -> std::path::PathBuf {
    let mut names: Vec<_> = tree(dir).into_keys().collect();
    names.sort();
    dir.join(&names[0])
}

fn copy_tree(from: &Path, to: &Path) {
    for rel in tree(from).into_keys() {
        let target = to.join(&rel);
        std::fs::create_dir_all(target.parent().unwrap()).unwrap();
        std::fs::copy(from.join(&rel), target).unwrap();
    }
}

/// BLAKE3 of every file under `out` (or of `out` itself, named `.`), by path relative to it.
fn digests(out: &Path) -> BTreeMap<String, String> {
    let files = match out.is_file() {
        true => BTreeMap::from([(".".to_string(), std::fs::read(out).unwrap())]),
        false => tree(out),
    };
    files
        .into_iter()
        .map(|(rel, bytes)| {
            let digest = blake3::hash(&masked(&rel, bytes));
            (rel, digest.to_hex().to_string())
        })
        .collect()
}

/// `rslam.json` with its `tool_version` masked, every other file as it is.
fn masked(rel: &str, bytes: Vec<u8>) -> Vec<u8> {
    if !(rel == "rslam.json" || rel.ends_with("/rslam.json")) {
        return bytes;
    }
    let text = String::from_utf8(bytes).unwrap();
    assert!(text.contains(VERSION_FIELD), "{rel}: no {VERSION_FIELD}");
    text.replace(VERSION_FIELD, "\"tool_version\": \"(masked)\"")
        .into_bytes()
}

/// `# adapter: NAME` then `CASE PATH DIGEST` lines.
fn format_table(adapter: &str, all: &[(String, BTreeMap<String, String>)]) -> String {
    let mut text = format!(
        "# Golden outputs of tests/cli/golden.rs: case, file, BLAKE3 (rslam.json's tool_version masked).\n# adapter: {adapter}\n"
    );
    for (case, files) in all {
        for (path, digest) in files {
            writeln!(text, "{case} {path} {digest}").unwrap();
        }
    }
    text
}

fn adapter_line(stderr: &str) -> String {
    stderr
        .lines()
        .find_map(|l| l.strip_prefix("adapter: "))
        .unwrap_or("(none printed)")
        .to_string()
}

#[test]
fn golden_outputs_keep_their_digests() {
    let ws = Workspace::new();
    let mut all = Vec::new();
    let mut adapter = None;
    for case in table() {
        if let Some(before) = case.before {
            before(&ws);
        }
        let args: Vec<&str> = case.args.iter().map(String::as_str).collect();
        let run = ws.rslam(&args);
        run.success();
        if let Some(fragment) = case.says {
            assert!(
                run.stderr().contains(fragment),
                "{}: {}",
                case.name,
                run.stderr()
            );
        }
        adapter.get_or_insert_with(|| adapter_line(&run.stderr()));
        all.push((case.name.to_string(), digests(&ws.path(case.out))));
    }
    let adapter = adapter.unwrap();
    let actual = format_table(&adapter, &all);
    if std::env::var("RSLAM_GOLDEN").as_deref() == Ok("record") {
        std::fs::write(DIGESTS, &actual).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(DIGESTS).expect("tests/cli/golden/digests.txt");
    let recorded_on = expected
        .lines()
        .find_map(|l| l.strip_prefix("# adapter: "))
        .unwrap_or("");
    assert_eq!(
        recorded_on, adapter,
        "the golden digests belong to the adapter '{recorded_on}', this run drew on '{adapter}'"
    );
    let expected: Vec<&str> = expected.lines().collect();
    let actual: Vec<&str> = actual.lines().collect();
    let missing: Vec<&&str> = expected.iter().filter(|l| !actual.contains(l)).collect();
    let extra: Vec<&&str> = actual.iter().filter(|l| !expected.contains(l)).collect();
    assert!(
        missing.is_empty() && extra.is_empty(),
        "outputs changed ({} lines recorded but not written, {} written but not recorded):\n--- recorded:\n{}\n--- written:\n{}",
        missing.len(),
        extra.len(),
        missing.iter().map(|l| l.to_string()).collect::<Vec<_>>().join("\n"),
        extra.iter().map(|l| l.to_string()).collect::<Vec<_>>().join("\n"),
    );
    assert!(all.len() >= 25 && expected.len() > 200, "the table shrank");
}
