//! Issue 4 end to end: trajectory deviations, fast motion and RGB–depth misalignment through
//! `rslam render` and `rslam perturb`, in both layouts, deterministic by seed.

use rslam_core::dataset::decode_depth_png;
use rslam_render::load_scene;
use rslam_render::raster::depth_agreement;
use rslam_render::raycast::RayCaster;

use crate::dataset_check::*;
use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

/// A tiny camera for the 2000-frame runs.
const TINY_CAMERA: &str = "32,24,16,16,15.5,11.5";

fn render(ws: &Workspace, out: &str, extra: &[&str]) {
    let mut args = vec!["render", "--scene", "room0", "--out", out];
    args.extend_from_slice(extra);
    ws.rslam(&args).success();
}

fn bytes(path: std::path::PathBuf) -> Vec<u8> {
    std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn fast_keeps_every_kth_pose_restamped() {
    let ws = Workspace::new();
    render(
        &ws,
        "fast",
        &["--camera", TINY_CAMERA, "--perturb", "fast:4"],
    );
    let root = ws.path("fast");
    let gt = replica_trajectory(&root);
    assert_eq!(gt.len(), 500);
    let clean = load_scene("room0").unwrap().default_trajectory.unwrap();
    let every_fourth: Vec<_> = clean.poses.iter().step_by(4).copied().collect();
    assert_poses_close(&gt.poses, &every_fourth, 1e-9);
    assert_eq!(files(&root.join("results"), "frame").len(), 500);
    let m = manifest(&root);
    assert_eq!(m.rgb_source[..3], [0, 4, 8]);
    assert_eq!(m.rate_hz, 20.0);
}

#[test]
fn misalign_pairs_rgb_with_depth_from_d_frames_earlier() {
    let ws = Workspace::new();
    let common = ["--camera", SMALL_CAMERA, "--frames", "24"];
    render(&ws, "clean", &common);
    render(
        &ws,
        "lag",
        &[&common[..], &["--perturb", "misalign:10"]].concat(),
    );
    let (clean, lag) = (ws.path("clean"), ws.path("lag"));
    for i in 0..24usize {
        let source = i.saturating_sub(10);
        assert_eq!(
            bytes(lag.join(format!("results/depth{i:06}.png"))),
            bytes(clean.join(format!("results/depth{source:06}.png"))),
            "depth of frame {i} must be clean depth {source}"
        );
        assert_eq!(
            bytes(lag.join(format!("results/frame{i:06}.jpg"))),
            bytes(clean.join(format!("results/frame{i:06}.jpg"))),
            "colour stays in place"
        );
    }
    assert_poses_close(
        &replica_trajectory(&lag).poses,
        &replica_trajectory(&clean).poses,
        1e-12,
    );
}

#[test]
fn misalign_in_tum_layout_keeps_capture_times_and_pairs_by_delivery() {
    let ws = Workspace::new();
    render(
        &ws,
        "lag",
        &[
            "--camera",
            SMALL_CAMERA,
            "--frames",
            "12",
            "--format",
            "tum",
            "--perturb",
            "misalign:5",
        ],
    );
    let root = ws.path("lag");
    let assoc = lines(&root.join("associations.txt"));
    assert_eq!(assoc.len(), 12);
    assert_eq!(
        assoc[7],
        "0.350000 rgb/0.350000.png 0.100000 depth/0.100000.png"
    );
    assert_eq!(
        assoc[2],
        "0.100000 rgb/0.100000.png 0.000000 depth/0.000000.png"
    );
    let depth_list = lines(&root.join("depth.txt"));
    assert_eq!(
        depth_list.first().map(String::as_str),
        Some("0.000000 depth/0.000000.png")
    );
    assert_eq!(
        depth_list.last().map(String::as_str),
        Some("0.300000 depth/0.300000.png"),
        "depth of the last 5 frames is never delivered"
    );
}

#[test]
fn dynamic_misalign_offsets_stay_within_one_frame_and_are_recorded() {
    let ws = Workspace::new();
    render(
        &ws,
        "dyn",
        &[
            "--camera",
            TINY_CAMERA,
            "--frames",
            "300",
            "--perturb",
            "misalign:10@dynamic",
            "--seed",
            "3",
        ],
    );
    let m = manifest(&ws.path("dyn"));
    let mut seen = std::collections::BTreeSet::new();
    for (i, (&rgb, &depth)) in m.rgb_source.iter().zip(&m.depth_source).enumerate() {
        assert_eq!(rgb, i);
        if i >= 11 {
            let lag = i - depth;
            assert!((9..=11).contains(&lag), "frame {i}: lag {lag}");
            seen.insert(lag);
        }
    }
    assert_eq!(seen.len(), 3, "all of D-1, D, D+1 occur");
}

#[test]
fn deviated_poses_are_the_ground_truth_and_depth_matches_them() {
    let ws = Workspace::new();
    render(
        &ws,
        "shaky",
        &[
            "--camera",
            SMALL_CAMERA,
            "--frames",
            "6",
            "--perturb",
            "rot:3,trans:0.05",
            "--seed",
            "7",
        ],
    );
    let root = ws.path("shaky");
    let gt = replica_trajectory(&root);
    let clean = load_scene("room0").unwrap().default_trajectory.unwrap();
    let moved: f64 = gt
        .poses
        .iter()
        .zip(&clean.poses)
        .map(|(a, b)| (a.translation - b.translation).length())
        .sum();
    assert!(
        moved / 6.0 > 0.02,
        "translation deviation of σ = 5 cm per axis must show: {moved}"
    );
    let scene = load_scene("room0").unwrap();
    let oracle = RayCaster::new(&scene);
    let k = rslam_core::Intrinsics::parse(SMALL_CAMERA).unwrap();
    for i in [0, 5] {
        let expected = oracle.depth_image(&gt.poses[i], &k);
        let step = 1.0 / 6553.5;
        let quantised = rslam_core::DepthImage {
            data: expected
                .data
                .iter()
                .map(|z| (z / step).round() * step)
                .collect(),
            ..expected
        };
        let a = depth_agreement(&replica_depth(&root, i), &quantised);
        assert_eq!(a.mask_mismatches, 0, "frame {i}: {a:?}");
        assert!(a.max_relative_error < 1e-3, "frame {i}: {a:?}");
    }
}

#[test]
fn everything_composes_in_either_layout_and_is_deterministic() {
    let ws = Workspace::new();
    let spec = "rot:1,trans:0.0125,gaussian_noise:3,depth_missing:5,fast:2,misalign:3";
    for format in ["replica", "tum"] {
        let args = [
            "--camera",
            SMALL_CAMERA,
            "--frames",
            "20",
            "--format",
            format,
            "--perturb",
            spec,
            "--seed",
            "11",
        ];
        render(&ws, &format!("{format}_a"), &args);
        render(&ws, &format!("{format}_b"), &args);
        let args_other_seed = [
            "--camera",
            SMALL_CAMERA,
            "--frames",
            "20",
            "--format",
            format,
            "--perturb",
            spec,
            "--seed",
            "12",
        ];
        render(&ws, &format!("{format}_c"), &args_other_seed);
        let (a, b, c) = (
            ws.path(&format!("{format}_a")),
            ws.path(&format!("{format}_b")),
            ws.path(&format!("{format}_c")),
        );
        let m = manifest(&a);
        assert_eq!(m.frame_count, 10);
        assert_eq!(
            m.depth_source[5], 4,
            "fast first: output 5 is source 10; its depth is output 2 = source 4"
        );
        assert_eq!(m.severities.len(), 2);
        let listing = |root: &std::path::Path| -> Vec<(String, Vec<u8>)> {
            let mut all = Vec::new();
            for dir in ["results", "rgb", "depth"] {
                if root.join(dir).is_dir() {
                    for f in files(&root.join(dir), "") {
                        all.push((
                            f.file_name().unwrap().to_string_lossy().into_owned(),
                            bytes(f),
                        ));
                    }
                }
            }
            all
        };
        assert_eq!(listing(&a), listing(&b), "{format}: same seed, same bytes");
        assert_ne!(
            listing(&a),
            listing(&c),
            "{format}: another seed, other bytes"
        );
        let gt_file = if format == "tum" {
            "groundtruth.txt"
        } else {
            "traj.txt"
        };
        assert_eq!(bytes(a.join(gt_file)), bytes(b.join(gt_file)));
    }
}

#[test]
fn stream_operations_work_on_existing_datasets_and_trajectory_ones_need_a_scene() {
    let ws = Workspace::new();
    render(
        &ws,
        "clean",
        &[
            "--camera",
            SMALL_CAMERA,
            "--frames",
            "16",
            "--format",
            "tum",
        ],
    );
    ws.rslam(&[
        "perturb",
        "--input",
        "clean",
        "--out",
        "fast",
        "--perturb",
        "fast:2,misalign:2",
    ])
    .success();
    let root = ws.path("fast");
    let assoc = lines(&root.join("associations.txt"));
    assert_eq!(assoc.len(), 8);
    assert_eq!(
        assoc[3],
        "0.150000 rgb/0.150000.png 0.050000 depth/0.050000.png"
    );
    let clean_depth = decode_depth_png(&ws.path("clean/depth/0.100000.png"), 5000.0).unwrap();
    let moved_depth = decode_depth_png(&root.join("depth/0.050000.png"), 5000.0).unwrap();
    assert_eq!(clean_depth, moved_depth, "output frame 1 is source frame 2");
    assert_eq!(tum_trajectory(&root).len(), 8);
    ws.rslam(&[
        "perturb",
        "--input",
        "clean",
        "--out",
        "rot",
        "--perturb",
        "rot:1",
    ])
    .fails_with(2, &["rot", "scene"]);
}
