//! Sensor effects end to end: `rslam render` draws them and records them in the manifest;
//! `rslam perturb` on a recorded dataset refuses them, naming the item. A lens is written into
//! the camera files.

use crate::dataset_check::*;
use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

#[test]
fn render_blurs_along_the_path_and_perturb_refuses_sensor_items() {
    let ws = Workspace::new();
    let render = |out: &str, spec: Option<&str>| {
        ws.render_room0(out, &["--camera", SMALL_CAMERA, "--frames", "3"], spec)
    };
    render("clean", None);
    render("sensor", Some("rolling_shutter:30,exposure:40,fog:1"));
    let root = ws.path("sensor");
    let manifest = manifest(&root);
    assert_eq!(
        manifest.perturbation,
        "exposure:40,rolling_shutter:30,fog:1"
    );
    assert_eq!(manifest.perturbation_parsed["exposure"]["ms"], 40.0);
    assert_eq!(manifest.perturbation_parsed["rolling_shutter"]["ms"], 30.0);
    assert_ne!(
        replica_rgb(&root, 1),
        replica_rgb(&ws.path("clean"), 1),
        "the moving camera's frame changes"
    );
    assert_eq!(
        replica_trajectory(&root).poses,
        replica_trajectory(&ws.path("clean")).poses,
        "ground truth stays the pose at the timestamp (mid-exposure, middle row)"
    );
    for item in ["exposure:20", "rolling_shutter:30"] {
        ws.rslam(&[
            "perturb",
            "--input",
            "clean",
            "--out",
            "refused",
            "--perturb",
            item,
        ])
        .fails_with(2, &[item, "scene"]);
    }
}

/// Through a lens: the frames change, the ground truth does not, the manifest records the lens,
/// cam_params.json (Replica) and orbslam3.yaml (TUM) carry it, and so does a perturbed copy; a
/// recorded dataset, and a EuRoC rig for a lens other than radtan, refuse it with one line naming
/// the item.
#[test]
fn render_through_a_lens_writes_it_into_the_camera_files() {
    let ws = Workspace::new();
    let lens = "distortion:equidistant(0.08,-0.03,0.01,-0.002)";
    let render = |out: &str, format: &str, spec: Option<&str>| {
        let args = [
            "--camera",
            SMALL_CAMERA,
            "--frames",
            "2",
            "--format",
            format,
        ];
        ws.render_room0(out, &args, spec)
    };
    render("clean", "replica", None);
    render("lens", "replica", Some(lens));
    let root = ws.path("lens");
    let recorded = manifest(&root);
    assert_eq!(recorded.perturbation, lens);
    assert_eq!(
        recorded.perturbation_parsed["distortion"]["model"],
        "equidistant"
    );
    assert_ne!(replica_rgb(&root, 1), replica_rgb(&ws.path("clean"), 1));
    assert_eq!(
        replica_trajectory(&root).poses,
        replica_trajectory(&ws.path("clean")).poses
    );
    let cam: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root.join("cam_params.json")).unwrap())
            .unwrap();
    assert_eq!(cam["camera"]["distortion_model"], "equidistant");
    assert_eq!(
        cam["camera"]["distortion"],
        serde_json::json!([0.08, -0.03, 0.01, -0.002])
    );
    render(
        "tum",
        "tum",
        Some("distortion:radtan(-0.2,0.05,0.001,-0.002)"),
    );
    let yaml = std::fs::read_to_string(ws.path("tum").join("orbslam3.yaml")).unwrap();
    for line in [
        "Camera.type: \"PinHole\"",
        "Camera1.k1: -2e-1",
        "Camera1.p2: -2e-3",
    ] {
        assert!(yaml.contains(line), "orbslam3.yaml lacks '{line}':\n{yaml}");
    }
    ws.rslam(&[
        "perturb",
        "--input",
        "lens",
        "--out",
        "fog",
        "--perturb",
        "fog:1",
    ])
    .success();
    let fog: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(ws.path("fog/cam_params.json")).unwrap())
            .unwrap();
    assert_eq!(fog["camera"], cam["camera"], "perturbing keeps the lens");
    assert_eq!(manifest(&ws.path("fog")).distortion, recorded.distortion);
    ws.rslam(&[
        "perturb",
        "--input",
        "clean",
        "--out",
        "refused",
        "--perturb",
        lens,
    ])
    .fails_with(2, &[lens, "scene"]);
    ws.rslam(&[
        "render",
        "--scene",
        "room0",
        "--rig",
        "stereo",
        "--format",
        "euroc",
        "--frames",
        "4",
        "--out",
        "rig",
        "--perturb",
        lens,
    ])
    .fails_with(2, &[lens, "use distortion:radtan(k1,k2,p1,p2)"]);
}
