//! Sensor effects end to end: `rslam render` draws them and records them in the manifest;
//! `rslam perturb` on a recorded dataset refuses them, naming the item.

use crate::dataset_check::*;
use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

#[test]
fn render_blurs_along_the_path_and_perturb_refuses_sensor_items() {
    let ws = Workspace::new();
    let render = |out: &str, spec: Option<&str>| {
        let mut args = vec![
            "render",
            "--scene",
            "room0",
            "--out",
            out,
            "--camera",
            SMALL_CAMERA,
            "--frames",
            "3",
        ];
        if let Some(spec) = spec {
            args.extend(["--perturb", spec]);
        }
        ws.rslam(&args).success();
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
