//! Light items end to end: a render records each frame's light per layer in the manifest, the
//! frames go dark where it says the lamps are off, `auto_exposure` after them follows the light,
//! and a mesh file, whose light is baked into its colours, refuses them naming the item.

use crate::dataset_check::mean_linear;
use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

fn manifest(ws: &Workspace, out: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(ws.path(&format!("{out}/rslam.json"))).unwrap();
    serde_json::from_str(&text).unwrap()
}

#[test]
fn lamps_switched_off_darken_the_frames_the_manifest_names() {
    let ws = Workspace::new();
    let args = ["--camera", SMALL_CAMERA, "--frames", "40", "--seed", "5"];
    ws.render_room0("clean", &args, None);
    ws.render_room0("dark", &args, Some("lights:1/0.4/0.3"));
    let light = &manifest(&ws, "dark")["extra"]["light"];
    let layers: Vec<&str> = (light["layers"].as_array().unwrap().iter())
        .map(|l| l.as_str().unwrap())
        .collect();
    assert_eq!(layers, ["lamp0", "lamp1", "daylight"]);
    let frames = light["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 40);
    let (mut dark, mut lit) = (0, 0);
    for (j, frame) in frames.iter().enumerate() {
        let lamps_off = layers
            .iter()
            .zip(frame.as_array().unwrap())
            .all(|(name, w)| *name == "daylight" || w[0].as_f64() == Some(0.0));
        let file = |out: &str| ws.path(&format!("{out}/results/frame{j:06}.jpg"));
        let ratio = mean_linear(&file("dark")) / mean_linear(&file("clean"));
        if lamps_off {
            dark += 1;
            assert!(
                ratio < 0.6,
                "frame {j}: lamps off but {ratio} of the clean light"
            );
        } else if frame[0][0].as_f64() == Some(1.0) && frame[1][0].as_f64() == Some(1.0) {
            lit += 1;
            assert!(
                (ratio - 1.0).abs() < 0.02,
                "frame {j}: lit but {ratio} of the clean light"
            );
        }
    }
    assert!(
        dark >= 3 && lit >= 3,
        "{dark} dark and {lit} lit frames of 40"
    );
}

#[test]
fn auto_exposure_follows_the_light_with_its_lag() {
    let ws = Workspace::new();
    let args = ["--camera", SMALL_CAMERA, "--frames", "40", "--seed", "5"];
    ws.render_room0("fixed", &args, Some("lights:1/0.4/0.3"));
    ws.render_room0("auto", &args, Some("lights:1/0.4/0.3,auto_exposure:1"));
    let frames = manifest(&ws, "fixed")["extra"]["light"]["frames"].clone();
    let dark: Vec<bool> = (frames.as_array().unwrap().iter())
        .map(|f| f[0][0].as_f64() == Some(0.0) && f[1][0].as_f64() == Some(0.0))
        .collect();
    let first = dark
        .iter()
        .position(|&d| d)
        .expect("a frame with every lamp off");
    let last = first + dark[first..].iter().take_while(|&&d| d).count() - 1;
    assert!(last >= first + 3, "a dark spell of several frames");
    let file = |out: &str, j: usize| ws.path(&format!("{out}/results/frame{j:06}.jpg"));
    let gain = |j| mean_linear(&file("auto", j)) / mean_linear(&file("fixed", j));
    // On the first dark frame the camera still exposes for the lit room; by the end of the
    // spell (a time constant of 2 frames) it has opened up.
    assert!(
        gain(last) > 1.3 * gain(first),
        "no adaptation: gain {} then {}",
        gain(first),
        gain(last)
    );
}

#[test]
fn a_mesh_file_refuses_light_items_by_name() {
    let ws = Workspace::new();
    ws.write("mesh.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    ws.write("path.txt", "0 0 0 0.5 0 0 0 1\n0.1 0 0 0.5 0 0 0 1\n");
    ws.rslam(&[
        "render",
        "--scene",
        "mesh.ply",
        "--traj",
        "path.txt",
        "--perturb",
        "daylight:2",
        "--out",
        "out",
    ])
    .fails_with(
        2,
        &[
            "daylight:2",
            "only the built-in scenes",
            "'mesh.ply' is a mesh file",
        ],
    );
    assert!(!ws.path("out").exists());
}
