//! People walking through a scene end to end: `actors` in the TUM layout (the walkers' poses in
//! the manifest, instance masks that say where depth changed, under a rolling shutter and a lens
//! too), and the refusals naming the item: a mesh file (no free floor), a recorded dataset (no scene), a bad value, a room too
//! crowded for the walkers asked for.

use rslam_core::dataset::{decode_depth_png, decode_mask_png};

use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

fn manifest(ws: &Workspace, out: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(ws.path(&format!("{out}/rslam.json"))).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn render_office1(ws: &Workspace, out: &str, spec: Option<&str>) {
    let mut args = vec![
        "render", "--scene", "office1", "--format", "tum", "--out", out,
    ];
    args.extend(["--camera", SMALL_CAMERA, "--frames", "160", "--seed", "3"]);
    args.extend(spec.iter().flat_map(|s| ["--perturb", s]));
    ws.rslam(&args).success();
}

#[test]
fn walkers_cross_the_view_of_a_tum_dataset_and_leave_the_other_frames_alone() {
    let ws = Workspace::new();
    render_office1(&ws, "clean", None);
    render_office1(&ws, "walkers", Some("actors:4"));
    let actors = &manifest(&ws, "walkers")["extra"]["actors"];
    let walkers = actors["walkers"].as_array().unwrap();
    assert_eq!(walkers.len(), 2, "actors:4 is two walkers");
    for w in walkers {
        let height = w["height_m"].as_f64().unwrap();
        assert!((1.55..=1.9).contains(&height), "{w}");
        assert_eq!(w["speed_m_s"].as_f64(), Some(1.2));
    }
    let frames = actors["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 160);
    // Walkers move at most their speed between frames (20 Hz).
    for pair in frames.windows(2) {
        for (a, b) in pair[0]
            .as_array()
            .unwrap()
            .iter()
            .zip(pair[1].as_array().unwrap())
        {
            let d = ((a[0].as_f64().unwrap() - b[0].as_f64().unwrap()).powi(2)
                + (a[1].as_f64().unwrap() - b[1].as_f64().unwrap()).powi(2))
            .sqrt();
            assert!(d <= 1.5 * 1.2 / 20.0 + 1e-3, "a walker jumped {d} m");
        }
    }
    let fractions = &manifest(&ws, "walkers")["extra"]["masks"]["dynamic_fraction"];
    let covered: Vec<f64> = (fractions.as_array().unwrap().iter())
        .map(|f| f.as_f64().unwrap())
        .collect();
    assert_eq!(covered.len(), 160);
    let frames = tum_frames(&ws, "walkers");
    check_masks_against_static_depth(&ws, ("walkers", "clean"), (&frames, 5000.0), 0.0, 2);
    let most = covered.iter().copied().fold(0.0, f64::max);
    assert!(
        most > 0.1 && most < 0.9,
        "walkers cover at most {most} of a frame"
    );
    assert!(
        covered.iter().any(|&c| c < most / 4.0),
        "the walkers' share varies"
    );
    check_dynamic_ate(&ws, "walkers", &covered);
    // `rslam scene stats` reads each frame's fraction from the dataset's manifest.
    let args = [
        "scene",
        "stats",
        "walkers",
        "--every",
        "1",
        "--json",
        "stats.json",
    ];
    ws.rslam(&args).success();
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(ws.path("stats.json")).unwrap()).unwrap();
    let listed: Vec<f64> = (stats["frames"].as_array().unwrap().iter())
        .map(|f| f["dynamic_fraction"].as_f64().unwrap())
        .collect();
    assert_eq!(listed.len(), covered.len());
    assert!((listed.iter().zip(&covered)).all(|(a, b)| (a - b).abs() < 1e-6));
}

/// `rslam scene stats SCENE --perturb actors:S`: each frame's dynamic fraction before any
/// dataset is written, as its instance mask gives it.
#[test]
fn scene_stats_give_each_frames_dynamic_fraction_under_actors() {
    let ws = Workspace::new();
    let args = [
        "scene",
        "stats",
        "office1",
        "--perturb",
        "actors:4",
        "--camera",
        SMALL_CAMERA,
        "--every",
        "40",
        "--json",
        "stats.json",
    ];
    let printed = ws.rslam(&args).success();
    assert!(printed.contains("dynamic pixels (%)"), "{printed}");
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(ws.path("stats.json")).unwrap()).unwrap();
    let fractions: Vec<f64> = (stats["frames"].as_array().unwrap().iter())
        .map(|f| {
            f["dynamic_fraction"]
                .as_f64()
                .expect("a fraction per frame")
        })
        .collect();
    let with_people = fractions.iter().filter(|&&f| f > 0.0).count();
    assert_eq!(
        stats["people"]["frames_with_people"].as_u64(),
        Some(with_people as u64)
    );
    assert!(
        with_people >= 3 && with_people < fractions.len(),
        "{fractions:?}"
    );
    ws.rslam(&["scene", "stats", ".", "--perturb", "actors:1"])
        .fails_with(2, &["--perturb", "not to a folder"]);
}

/// `rslam eval --dynamic-above` on the dataset's own ground truth, against an estimate 5 cm off
/// on the frames where walkers cover more than 5 % of the view (unaligned, so that the error is
/// exactly that): those frames, and their error.
fn check_dynamic_ate(ws: &Workspace, walkers: &str, covered: &[f64]) {
    let gt = std::fs::read_to_string(ws.path(&format!("{walkers}/groundtruth.txt"))).unwrap();
    let poses = gt.lines().filter(|l| !l.starts_with('#'));
    let est: String = (poses.zip(covered))
        .map(|(line, &fraction)| {
            let mut v: Vec<f64> = line.split(' ').map(|x| x.parse().unwrap()).collect();
            v[1] += if fraction > 0.05 { 0.05 } else { 0.0 };
            let text: Vec<String> = v.iter().map(|x| format!("{x:.6}")).collect();
            text.join(" ") + "\n"
        })
        .collect();
    ws.write("est.txt", &est);
    let gt_path = format!("{walkers}/groundtruth.txt");
    let args = [
        "eval",
        "est.txt",
        &gt_path,
        "--dynamic-above",
        "0.05",
        "--align",
        "none",
        "--json",
    ];
    let report: serde_json::Value = serde_json::from_str(&ws.rslam(&args).success()).unwrap();
    let dynamic = &report["dynamic_ate"];
    let expected = covered.iter().filter(|&&c| c > 0.05).count();
    assert!(expected >= 5, "{expected} frames with walkers");
    assert_eq!(dynamic["dynamic_frames"].as_u64(), Some(expected as u64));
    assert_eq!(dynamic["ate"]["n"].as_u64(), Some(expected as u64));
    let (on_them, all) = (
        dynamic["ate"]["rmse"].as_f64().unwrap(),
        report["ate"]["rmse"].as_f64().unwrap(),
    );
    let share = expected as f64 / covered.len() as f64;
    assert!(
        (on_them - 0.05).abs() < 1e-5,
        "ATE {on_them} on dynamic frames"
    );
    assert!((all - 0.05 * share.sqrt()).abs() < 1e-5, "ATE {all} on all");
}

/// Each frame's mask and depth file in the TUM dataset `out`: masks as `mask.txt` lists them,
/// one per colour frame at its time, and the depth of that time.
fn tum_frames(ws: &Workspace, out: &str) -> Vec<(String, String)> {
    let list = std::fs::read_to_string(ws.path(&format!("{out}/mask.txt"))).unwrap();
    let masks: Vec<(String, String)> = (list.lines().filter(|l| !l.starts_with('#')))
        .map(|l| {
            let (t, name) = l.split_once(' ').unwrap();
            (t.to_string(), name.to_string())
        })
        .collect();
    let rgb = std::fs::read_to_string(ws.path(&format!("{out}/rgb.txt"))).unwrap();
    let rgb_times: Vec<&str> = (rgb.lines().filter(|l| !l.starts_with('#')))
        .map(|l| l.split(' ').next().unwrap())
        .collect();
    let mask_times: Vec<&str> = masks.iter().map(|(t, _)| t.as_str()).collect();
    assert_eq!(
        mask_times, rgb_times,
        "one mask per colour frame, at its time"
    );
    (masks.into_iter())
        .map(|(t, name)| (name, format!("depth/{t}.png")))
        .collect()
}

/// The instance masks of the dataset `walkers` (`frames`: each frame's mask and depth file,
/// depth stored at `scale` per metre) against the depth of `walkers` and of `clean`, the same
/// job without walkers: outside the mask depth is the static render's (bit for bit, or within
/// `blend` of it where depth blends a pixel's neighbours); inside, a walker only ever hides the
/// room (never farther than `blend` of the room's depth, nearer on most pixels); the manifest's
/// dynamic fraction is the mask's; ids go from 1 to the walker count, each seen.
fn check_masks_against_static_depth(
    ws: &Workspace,
    (walkers, clean): (&str, &str),
    (frames, scale): (&[(String, String)], f64),
    blend: f32,
    walker_count: u16,
) {
    let fractions = manifest(ws, walkers)["extra"]["masks"]["dynamic_fraction"].clone();
    let mut seen = vec![false; usize::from(walker_count) + 1];
    let (mut nearer, mut on_walkers) = (0usize, 0usize);
    assert_eq!(fractions.as_array().unwrap().len(), frames.len());
    for (j, (name, depth_file)) in frames.iter().enumerate() {
        let mask = decode_mask_png(&ws.path(&format!("{walkers}/{name}"))).expect("mask png");
        let depth_of = |out: &str| {
            let path = ws.path(&format!("{out}/{depth_file}"));
            decode_depth_png(&path, scale).expect("depth png")
        };
        let (still, moving) = (depth_of(clean), depth_of(walkers));
        assert_eq!((mask.width, mask.height), (moving.width, moving.height));
        for (p, &id) in mask.data.iter().enumerate() {
            assert!(id <= walker_count, "{name}: id {id}");
            seen[usize::from(id)] = true;
            let (c, w) = (still.data[p], moving.data[p]);
            if id == 0 {
                assert!(
                    (w - c).abs() <= blend * c,
                    "{name}: depth moved outside the mask"
                );
            } else {
                on_walkers += 1;
                assert!(
                    c == 0.0 || w <= c * (1.0 + blend),
                    "{name}: a walker behind the room"
                );
                nearer += usize::from(w < c);
            }
        }
        let fraction = fractions[j].as_f64().unwrap();
        assert!((fraction - mask.dynamic_fraction()).abs() < 1e-6, "{name}");
    }
    assert!(seen.iter().all(|&s| s), "ids seen: {seen:?}");
    assert!(
        nearer as f64 > 0.95 * on_walkers as f64,
        "{nearer} of {on_walkers} walker pixels are nearer than the room"
    );
}

/// Under a rolling shutter each row's mask is of that row's read-out instant, as its depth is;
/// through a lens the mask is resampled nearest-neighbour, while depth blends the four wide
/// texels round a pixel where they agree within 2 % (a shoe on the floor): a walker's sliver
/// narrower than a pixel moves depth that little without reaching the mask.
#[test]
fn masks_follow_each_row_under_a_rolling_shutter_and_the_lens() {
    let ws = Workspace::new();
    let sensor = "rolling_shutter:30,distortion:radtan(-0.2,0.05,0,0)";
    render_office1(&ws, "clean", Some(sensor));
    render_office1(&ws, "walkers", Some(&format!("actors:4,{sensor}")));
    let frames = tum_frames(&ws, "walkers");
    check_masks_against_static_depth(&ws, ("walkers", "clean"), (&frames, 5000.0), 0.02, 2);
}

#[test]
fn world_items_are_refused_without_a_free_floor_a_scene_or_room_and_for_bad_values() {
    let ws = Workspace::new();
    ws.write("mesh.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    ws.write("path.txt", "0 0 0 0.5 0 0 0 1\n0.1 0 0 0.5 0 0 0 1\n");
    let mesh = [
        "render", "--scene", "mesh.ply", "--traj", "path.txt", "--out", "out",
    ];
    for item in ["actors:2", "objects:2"] {
        refused(
            &ws,
            &mesh,
            item,
            &[item, "free floor", "'mesh.ply' is a mesh file"],
        );
    }
    let args = ["--camera", SMALL_CAMERA, "--frames", "4"];
    ws.render_room0("data", &args, None);
    let perturb = ["perturb", "--input", "data", "--out", "p"];
    refused(&ws, &perturb, "actors:1", &["actors:1", "needs a scene"]);
    let room0 = [
        "render", "--scene", "room0", "--out", "bad", "--frames", "40",
    ];
    refused(
        &ws,
        &room0,
        "actors:9/1/1",
        &["actors:9/1/1", "COUNT/SPEED/NEAR"],
    );
    let objects = ["objects:7/1/1", "COUNT/SPEED/NEAR", "1-6 things moved"];
    refused(&ws, &room0, "objects:7/1/1", &objects);
    let crowded = [
        "render", "--scene", "room1", "--out", "crowded", "--frames", "100",
    ];
    let words = ["room1", "no path over the free floor", "fewer walkers"];
    refused(&ws, &crowded, "actors:8/1.4/0.4", &words);
}

/// `command --perturb item` fails naming each of `words` and leaves no output folder.
fn refused(ws: &Workspace, command: &[&str], item: &str, words: &[&str]) {
    ws.rslam(&[command, &["--perturb", item]].concat())
        .fails_with(2, words);
    let out = command[command
        .iter()
        .position(|&a| a == "--out")
        .expect("an --out")
        + 1];
    assert!(!ws.path(out).exists(), "{item} left {out} behind");
}

#[test]
fn both_cameras_of_a_stereo_rig_see_the_same_walkers() {
    let ws = Workspace::new();
    let render = |out: &str, spec: Option<&str>| {
        let mut args = vec!["render", "--scene", "office0", "--rig", "stereo-imu"];
        args.extend([
            "--format", "euroc", "--frames", "60", "--seed", "2", "--out", out,
        ]);
        args.extend(spec.iter().flat_map(|s| ["--perturb", s]));
        ws.rslam(&args).success();
    };
    render("clean", None);
    render("walkers", Some("actors:5"));
    let fractions = manifest(&ws, "walkers")["extra"]["masks"]["dynamic_fraction"].clone();
    // A frame differs from the clean one exactly when its mask has a walker in it.
    let changed = |camera: &str| -> Vec<bool> {
        let folder = format!("mav0/{camera}/data");
        let mut names = crate::harness::sorted_names(&ws.path(&format!("clean/{folder}")));
        names.sort_by_key(|name| name.trim_end_matches(".png").parse::<u64>().unwrap());
        let listed = fractions[camera].as_array().expect("a fraction per frame");
        assert_eq!(listed.len(), names.len(), "{camera}");
        (names.iter().zip(listed))
            .map(|(name, fraction)| {
                let read =
                    |out: &str| std::fs::read(ws.path(&format!("{out}/{folder}/{name}"))).unwrap();
                let changed = read("clean") != read("walkers");
                let path = ws.path(&format!("walkers/mav0/{camera}/mask/{name}"));
                let mask = decode_mask_png(&path).expect("a mask per frame");
                let dynamic = mask.dynamic_fraction();
                assert!(
                    (fraction.as_f64().unwrap() - dynamic).abs() < 1e-6,
                    "{name}"
                );
                assert_eq!(
                    changed,
                    dynamic > 0.0,
                    "{camera}/{name}: changed, or a mask"
                );
                changed
            })
            .collect()
    };
    let (left, right) = (changed("cam0"), changed("cam1"));
    let frames = manifest(&ws, "walkers")["extra"]["actors"]["frames"].clone();
    assert_eq!(
        frames.as_array().unwrap().len(),
        left.len(),
        "a pose per cam0 frame"
    );
    let both = left.iter().zip(&right).filter(|(l, r)| **l && **r).count();
    let either = left.iter().zip(&right).filter(|(l, r)| **l || **r).count();
    assert!(either >= 5, "walkers seen in {either} of 60 frames");
    // 11 cm apart, the cameras see nearly the same: a walker at the edge of one view only.
    assert!(
        both as f64 >= 0.8 * either as f64,
        "{both} of {either} frames in both views"
    );
}

/// The Replica layout puts each frame's mask beside its colour and depth, numbered as they are.
#[test]
fn replica_masks_lie_beside_their_frames() {
    let ws = Workspace::new();
    let render = |out: &str, spec: &[&str]| {
        let scene = ["render", "--scene", "office2", "--camera", SMALL_CAMERA];
        let args = ["--frames", "100", "--seed", "2", "--out", out];
        ws.rslam(&[&scene[..], &args, spec].concat()).success();
    };
    render("clean", &[]);
    render("walkers", &["--perturb", "actors:2/1.1/0.8"]);
    let frames: Vec<(String, String)> = (0..100)
        .map(|j| {
            let mask = format!("results/mask{j:06}.png");
            (mask, format!("results/depth{j:06}.png"))
        })
        .collect();
    check_masks_against_static_depth(&ws, ("walkers", "clean"), (&frames, 6553.5), 0.0, 2);
    let files = crate::harness::sorted_names(&ws.path("walkers/results"));
    assert_eq!(
        files.len(),
        3 * 100,
        "a colour, a depth and a mask per frame"
    );
}

/// A run killed mid-way keeps its frames and masks; the resumed run (walkers and the swinging
/// door planned again) reads the kept masks' dynamic fractions back and ends with the bytes of an
/// uninterrupted run, in both layouts with masks.
#[test]
fn a_killed_render_with_walkers_and_a_door_resumes_to_the_same_bytes() {
    let tum = [
        "render",
        "--scene",
        "office1",
        "--format",
        "tum",
        "--camera",
        SMALL_CAMERA,
    ];
    let euroc = [
        "render", "--scene", "office0", "--rig", "stereo", "--format", "euroc",
    ];
    for (command, watch) in [(&tum[..], "mask"), (&euroc[..], "mav0/cam0/mask")] {
        let args = [
            command,
            &[
                "--frames",
                "300",
                "--seed",
                "3",
                "--perturb",
                "actors:4,objects:1",
            ],
            &["--out", "ds"],
        ]
        .concat();
        let whole = Workspace::new();
        whole.rslam(&args).success();
        let killed = Workspace::new();
        crate::resume::kill_mid_run(&killed, &args, "ds", watch, "");
        killed.rslam(&args).success();
        crate::dataset_check::assert_same_tree(&whole.path("ds"), &killed.path("ds"));
    }
}

/// A box (0.36 × 0.36 × 0.8 m, its origin on the floor at its centre) with coloured faces.
pub const BOX_PLY: &str = "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 12\nproperty list uchar int vertex_indices\nend_header\n-0.18 -0.18 0 200 80 40\n0.18 -0.18 0 200 80 40\n0.18 0.18 0 200 80 40\n-0.18 0.18 0 200 80 40\n-0.18 -0.18 0.8 200 80 40\n0.18 -0.18 0.8 200 80 40\n0.18 0.18 0.8 200 80 40\n-0.18 0.18 0.8 200 80 40\n3 0 2 1\n3 0 3 2\n3 4 5 6\n3 4 6 7\n3 0 1 5\n3 0 5 4\n3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n";

/// `--actor MESH PATH`: a user's box carried along a path over the free floor (a walker's, taken
/// from another job's manifest) is drawn with its own mask id, hides the room only where its
/// mask says, and is recorded with its files' BLAKE3; a path through a wall or the camera is
/// refused naming the path file's lines, and unreadable files naming the file; beside walkers
/// and objects, they give way to it.
#[test]
fn a_users_actor_follows_its_path_and_bad_paths_are_refused_by_line() {
    let ws = Workspace::new();
    render_office1(&ws, "walkers", Some("actors:1/1/1.2"));
    let frames = manifest(&ws, "walkers")["extra"]["actors"]["frames"].clone();
    let mut path = String::from("# t x y z qx qy qz qw\n");
    for (j, frame) in frames.as_array().unwrap().iter().enumerate() {
        let (x, y) = (frame[0][0].as_f64().unwrap(), frame[0][1].as_f64().unwrap());
        path.push_str(&format!("{:.6} {x} {y} 0 0 0 0 1\n", j as f64 * 0.05));
    }
    ws.write("box.ply", BOX_PLY);
    ws.write("path.txt", &path);
    render_office1(&ws, "clean", None);
    let with_box = |out: &str, mesh: &str, path: &str| {
        let mut args = vec![
            "render", "--scene", "office1", "--format", "tum", "--out", out,
        ];
        args.extend(["--camera", SMALL_CAMERA, "--frames", "160", "--seed", "3"]);
        args.extend(["--actor", mesh, path]);
        ws.rslam(&args)
    };
    with_box("box", "box.ply", "path.txt").success();
    let frames = tum_frames(&ws, "box");
    check_masks_against_static_depth(&ws, ("box", "clean"), (&frames, 5000.0), 0.0, 1);
    let user = &manifest(&ws, "box")["extra"]["actors"]["user"][0];
    let digest = rslam_core::dataset::blake3_hex(BOX_PLY.as_bytes());
    assert_eq!(user["mesh_blake3"].as_str(), Some(digest.as_str()));
    assert_eq!(user["path"].as_str(), Some("path.txt"));

    // Pose 11 (line 12) moved 6 m sideways, out of the room.
    let mut lines: Vec<String> = path.lines().map(String::from).collect();
    let mut fields: Vec<f64> = lines[11].split(' ').map(|v| v.parse().unwrap()).collect();
    fields[1] += 6.0;
    lines[11] = fields
        .iter()
        .map(|v| v.to_string())
        .collect::<Vec<_>>()
        .join(" ");
    ws.write("wall.txt", &(lines.join("\n") + "\n"));
    with_box("w", "box.ply", "wall.txt")
        .fails_with(2, &["wall.txt", "lines 11-12", "wall or furniture"]);
    // Standing where the camera starts.
    let gt = std::fs::read_to_string(ws.path("clean/groundtruth.txt")).unwrap();
    let first = gt.lines().find(|l| !l.starts_with('#')).unwrap();
    let at: Vec<&str> = first.split(' ').collect();
    ws.write("camera.txt", &format!("0 {} {} 0 0 0 0 1\n", at[1], at[2]));
    with_box("c", "box.ply", "camera.txt")
        .fails_with(2, &["camera.txt", "line 1", "from the camera"]);
    with_box("m", "missing.ply", "path.txt").fails_with(2, &["missing.ply"]);
    ws.write("three.txt", "0 1 2\n");
    with_box("p", "box.ply", "three.txt").fails_with(2, &["three.txt:1"]);
    for out in ["w", "c", "m", "p"] {
        assert!(
            !ws.path(out).exists(),
            "{out}: a refused job writes nothing"
        );
    }
    // Beside walkers and objects: the walker of the same seed, whose path the box now takes,
    // gives way to it; ids go walker, box, door.
    let mut args = vec![
        "render", "--scene", "office1", "--format", "tum", "--out", "b",
    ];
    args.extend(["--camera", SMALL_CAMERA, "--frames", "160", "--seed", "3"]);
    args.extend([
        "--perturb",
        "actors:1/1/1.2,objects:1",
        "--actor",
        "box.ply",
        "path.txt",
    ]);
    ws.rslam(&args).success();
    let actors = &manifest(&ws, "b")["extra"]["actors"];
    assert_eq!(actors["user"].as_array().unwrap().len(), 1);
    assert_eq!(actors["objects"][0]["kind"].as_str(), Some("door"));
    let reach = actors["walkers"][0]["footprint_radius_m"].as_f64().unwrap()
        + actors["user"][0]["footprint_radius_m"].as_f64().unwrap();
    let (walker, rigid) = (
        actors["frames"].as_array().unwrap(),
        actors["rigid_frames"].as_array().unwrap(),
    );
    for (w, r) in walker.iter().zip(rigid) {
        let d = (w[0][0].as_f64().unwrap() - r[0][0].as_f64().unwrap())
            .hypot(w[0][1].as_f64().unwrap() - r[0][1].as_f64().unwrap());
        assert!(d >= reach, "the walker comes {d} m from the box");
    }
    let mut ids = [false; 4];
    for (name, _) in tum_frames(&ws, "b") {
        let mask = decode_mask_png(&ws.path(&format!("b/{name}"))).unwrap();
        for &id in &mask.data {
            ids[usize::from(id)] = true;
        }
    }
    assert!(
        ids[..3].iter().all(|&s| s),
        "the walker and the box are seen: {ids:?}"
    );
}
