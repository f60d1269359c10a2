//! Things moved through a scene end to end (`objects`): the door and chairs beside walkers in
//! the TUM layout (each object in the manifest with its pose per frame, masks that say where
//! depth changed); their refusals are with the walkers' (`actors.rs`).

use rslam_core::dataset::{decode_depth_png, decode_mask_png};

use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

fn render_office2(ws: &Workspace, out: &str, spec: Option<&str>) {
    let mut args = vec![
        "render", "--scene", "office2", "--format", "tum", "--out", out,
    ];
    args.extend(["--camera", SMALL_CAMERA, "--frames", "300", "--seed", "3"]);
    args.extend(spec.iter().flat_map(|s| ["--perturb", s]));
    ws.rslam(&args).success();
}

/// Each quaternion's angle from the first frame's, radians.
fn turned(first: &[f64], now: &[f64]) -> f64 {
    let dot: f64 = (3..7).map(|i| first[i] * now[i]).sum();
    2.0 * dot.abs().min(1.0).acos()
}

/// office2 with `actors:1/1/1.2` and `objects:4` (one walker; the door, a box carried and a chair):
/// id 1 the walker, 2 the box's carrier, 3 the door (its leaf and the opening it leaves), 4 the
/// chair; outside the masks depth
/// is the static render's, bit for bit, except farther where the open door no longer stands
/// (only while it is open, and little of the frame); a chair only ever hides the room; a chair
/// moves at most its top speed between frames and the door turns about a fixed hinge.
#[test]
fn a_door_and_chairs_move_beside_walkers_with_masks_that_say_where() {
    let ws = Workspace::new();
    render_office2(&ws, "clean", None);
    render_office2(&ws, "moved", Some("actors:1/1/1.2,objects:4"));
    let text = std::fs::read_to_string(ws.path("moved/rslam.json")).unwrap();
    let manifest: serde_json::Value = serde_json::from_str(&text).unwrap();
    let actors = &manifest["extra"]["actors"];
    let kinds: Vec<&str> = (actors["objects"].as_array().unwrap().iter())
        .map(|o| o["kind"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["door", "chair"]);
    let carrying: Vec<bool> = (actors["walkers"].as_array().unwrap().iter())
        .map(|w| w["carries_box"].as_bool().unwrap())
        .collect();
    assert_eq!(
        carrying,
        [false, true],
        "the walker, then the box's carrier"
    );
    let door_moves = actors["objects"][0]["moves_s"].as_array().unwrap().clone();
    let opens = door_moves[0][0].as_f64().unwrap();
    let shut = door_moves[1][1].as_f64().unwrap();
    let poses: Vec<Vec<Vec<f64>>> = serde_json::from_value(actors["rigid_frames"].clone()).unwrap();
    assert_eq!(poses.len(), 300);
    for pair in poses.windows(2) {
        for (a, b) in pair[0][1..].iter().zip(&pair[1][1..]) {
            let step = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
            assert!(step <= 0.7 / 20.0 + 1e-3, "a chair jumped {step} m");
        }
        assert_eq!(pair[0][0][..3], pair[1][0][..3], "the door's hinge stays");
    }
    let widest = (poses.iter())
        .map(|p| turned(&poses[0][0], &p[0]))
        .fold(0.0, f64::max);
    assert!(widest > 0.6, "the door opens {widest} rad");
    let mask_list = std::fs::read_to_string(ws.path("moved/mask.txt")).unwrap();
    let masks: Vec<(f64, String)> = (mask_list.lines().filter(|l| !l.starts_with('#')))
        .map(|l| {
            let (t, name) = l.split_once(' ').unwrap();
            (t.parse().unwrap(), name.to_string())
        })
        .collect();
    assert_eq!(masks.len(), 300);
    let mut seen = [false; 5];
    let (mut farther_outside, mut nearer, mut on_chairs) = (0usize, 0usize, 0usize);
    for (t, name) in &masks {
        let mask = decode_mask_png(&ws.path(&format!("moved/{name}"))).unwrap();
        let depth_of = |out: &str| {
            let path = ws.path(&format!("{out}/depth/{}.png", &name[5..name.len() - 4]));
            decode_depth_png(&path, 5000.0).unwrap()
        };
        let (still, moved) = (depth_of("clean"), depth_of("moved"));
        let door_open = (opens..shut + 0.05).contains(t);
        let mut outside = 0;
        for (p, &id) in mask.data.iter().enumerate() {
            assert!(id <= 4, "{name}: id {id}");
            seen[usize::from(id)] = true;
            let (c, m) = (still.data[p], moved.data[p]);
            if id == 0 {
                if m != c {
                    assert!(
                        door_open && (c > 0.0 && m > c),
                        "{name}: depth moved outside the mask at {t} s"
                    );
                    outside += 1;
                }
            } else if id == 4 {
                on_chairs += 1;
                nearer += usize::from(m < c);
                assert!(c == 0.0 || m <= c, "{name}: a chair behind the room");
            }
        }
        assert!(
            outside * 50 < mask.data.len(),
            "{name}: {outside} pixels where the door stood"
        );
        farther_outside += outside;
    }
    assert!(seen.iter().all(|&s| s), "ids seen: {seen:?}");
    assert!(
        farther_outside > 0,
        "the wall behind the door shows when it opens"
    );
    assert!(
        nearer as f64 > 0.95 * on_chairs as f64,
        "{nearer} of {on_chairs} chair pixels nearer"
    );
}
