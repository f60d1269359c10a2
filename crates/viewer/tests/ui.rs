//! The viewer driven like a person would, through egui_kittest (AccessKit) and rendered with
//! egui-wgpu on the same device as the pipeline (lavapipe here): a scene tuned with the
//! perturbation panel, a dataset scrubbed on the timeline, the main window against a snapshot,
//! and bad input shown in the window.

use std::path::Path;

use egui::accesskit::Role;
use egui_kittest::kittest::Queryable;
use egui_kittest::{wgpu::WgpuTestRenderer, Harness, SnapshotOptions};
use rslam_core::dataset::{DatasetFormat, DepthPng};
use rslam_core::trajectory_io::{read_trajectory, write_tum};
use rslam_core::{Intrinsics, Trajectory};
use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_perturb::PerturbSpec;
use rslam_pipeline::{run, Job, SceneJob, Sensors, Silent, Source};
use rslam_viewer::{render_state_for, Session, ViewOptions, ViewSource, ViewerApp};

/// Small frames keep the tests fast; the viewer does not care about the size.
const CAMERA: Intrinsics = Intrinsics {
    width: 120,
    height: 68,
    fx: 60.0,
    fy: 60.0,
    cx: 59.5,
    cy: 33.5,
};

const WINDOW: egui::Vec2 = egui::vec2(1100.0, 640.0);

fn context() -> GpuContext {
    GpuContext::new(&AdapterChoice::default())
        .unwrap_or_else(|e| panic!("these tests need an adapter (lavapipe is fine): {e}"))
}

fn scene_job(frames: usize) -> SceneJob {
    SceneJob {
        scene: "room0".into(),
        trajectory: None,
        frames: Some(frames),
        camera: CAMERA,
        rate_hz: 20.0,
        spec: PerturbSpec::default(),
        seed: 0,
        agent: None,
        capture: Default::default(),
        actor_files: Vec::new(),
    }
}

fn harness(options: &ViewOptions) -> Harness<'static, ViewerApp> {
    let ctx = context();
    let render_state = render_state_for(&ctx).unwrap();
    let session = Session::open(ctx, options);
    let app = ViewerApp::new(session, render_state.clone());
    let mut harness = Harness::builder()
        .with_size(WINDOW)
        .renderer(WgpuTestRenderer::from_render_state(render_state))
        .build_ui_state(|ui, app: &mut ViewerApp| app.ui(ui), app);
    harness.run();
    harness
}

/// The frame panel's colour image as the window shows it (inset by a pixel), and where it is.
fn shown_image(harness: &mut Harness<'_, ViewerApp>) -> (egui::Rect, image::RgbaImage) {
    let rect = harness.state().frame_rects()[0];
    let window = harness.render().expect("the wgpu renderer renders");
    let ppp = harness.ctx.pixels_per_point();
    let (x, y) = (
        (rect.left() * ppp) as u32 + 1,
        (rect.top() * ppp) as u32 + 1,
    );
    let (w, h) = (
        (rect.width() * ppp) as u32 - 2,
        (rect.height() * ppp) as u32 - 2,
    );
    (
        rect,
        image::imageops::crop_imm(&window, x, y, w, h).to_image(),
    )
}

/// The left and right thirds of an image (either side of a split in the middle).
fn thirds(image: &image::RgbaImage) -> [image::RgbaImage; 2] {
    let (w, h) = image.dimensions();
    let crop = |x| image::imageops::crop_imm(image, x, 0, w / 3, h).to_image();
    [crop(0), crop(w - w / 3)]
}

/// Mean absolute difference per channel (0–255).
fn mean_abs_difference(a: &image::RgbaImage, b: &image::RgbaImage) -> f64 {
    assert_eq!(a.dimensions(), b.dimensions());
    let sum: u64 = a
        .as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(x, y)| x.abs_diff(*y) as u64)
        .sum();
    sum as f64 / a.as_raw().len() as f64
}

/// A mean difference (0–255) between two shown images that counts as a visible change; one
/// severity step of fog in a small room changes the perturbed half by about 1.5.
const VISIBLE_CHANGE: f64 = 0.5;

#[test]
fn fog_added_in_the_panel_and_its_slider_moved_changes_the_frame() {
    let options = ViewOptions {
        source: ViewSource::Scene(Box::new(scene_job(3))),
        spec: PerturbSpec::default(),
        seed: 0,
        estimate: None,
    };
    let mut harness = harness(&options);
    assert_eq!(harness.state().session.error, None);
    harness.get_by_label("(clean)");

    harness.get_by_label("add perturbation").click();
    harness.run();
    harness.get_by_label("fog").click();
    harness.run();
    harness.get_by_label("fog:3");
    let (rect3, fog3) = shown_image(&mut harness);

    harness
        .get_by_role_and_label(Role::Slider, "fog severity")
        .set_value_accesskit(4.0);
    harness.run();
    harness.get_by_label("fog:4");
    assert_eq!(harness.state().session.spec_string(), "fog:4");
    let (rect4, fog4) = shown_image(&mut harness);
    assert_eq!(
        rect3, rect4,
        "the layout stayed, so what changed is the frame"
    );

    // The split is in the middle: clean on the left, perturbed on the right.
    let ([clean3, foggy3], [clean4, foggy4]) = (thirds(&fog3), thirds(&fog4));
    let moved = mean_abs_difference(&foggy3, &foggy4);
    assert!(
        moved > VISIBLE_CHANGE,
        "fog 3 → 4 changed the perturbed side by {moved}"
    );
    assert!(clean3 == clean4, "the clean side did not change");

    // The split slider at either end shows the whole frame clean, then perturbed.
    let split = |harness: &mut Harness<'_, ViewerApp>, at: f64| {
        harness
            .get_by_role_and_label(Role::Slider, "split clean | perturbed")
            .set_value_accesskit(at);
        harness.run();
        shown_image(harness).1
    };
    let (all_clean, all_foggy) = (split(&mut harness, 1.0), split(&mut harness, 0.0));
    let fog = mean_abs_difference(&all_clean, &all_foggy);
    assert!(fog > VISIBLE_CHANGE, "fog:4 changed the frame by {fog}");
    assert!(
        thirds(&all_foggy)[1] == foggy4,
        "the perturbed side is the same frame"
    );
}

/// A Replica dataset of `frames` frames of room0, made by the pipeline; returns its ground truth.
fn make_dataset(dir: &Path, frames: usize) -> Trajectory {
    let ctx = context();
    let job = Job {
        source: Source::Scene {
            scene: scene_job(frames),
            sensors: Sensors::Camera {
                format: DatasetFormat::Replica,
                depth_png: DepthPng::Fast,
                bag: Default::default(),
            },
        },
        out: dir.to_path_buf(),
        force: false,
        command: vec!["test".into()],
    };
    run(&ctx, &job, &Silent).unwrap();
    read_trajectory(&dir.join("traj.txt"), None)
        .unwrap()
        .trajectory
}

#[test]
fn scrubbing_a_dataset_moves_the_frame_index_and_the_trajectory_marker() {
    let dir = tempfile::tempdir().unwrap();
    let dataset = dir.path().join("ds");
    let ground_truth = make_dataset(&dataset, 6);
    // The estimate: the ground truth moved rigidly, so its ATE after alignment is 0.
    let mut estimate = ground_truth.clone();
    for pose in &mut estimate.poses {
        pose.translation += glam::DVec3::new(0.3, -0.2, 1.0);
    }
    let estimate_path = dir.path().join("est.txt");
    write_tum(&estimate_path, &estimate).unwrap();
    let options = ViewOptions {
        source: ViewSource::Dataset(dataset),
        spec: PerturbSpec::parse("gaussian_noise:2").unwrap(),
        seed: 0,
        estimate: Some(estimate_path),
    };
    let mut harness = harness(&options);
    assert_eq!(harness.state().session.error, None);
    harness.get_by_label("frame 0 / 6");
    harness.get_by_label_contains("ATE RMSE 0.0000 m over 6 poses");

    harness
        .get_by_role_and_label(Role::Slider, "scrub")
        .set_value_accesskit(4.0);
    harness.run();
    harness.get_by_label("frame 4 / 6");
    let session = &harness.state().session;
    assert_eq!(session.index(), 4);
    let marker = session.marker().expect("the marker is on the ground truth");
    assert_eq!(marker, ground_truth.poses[4]);
    let p = marker.translation;
    harness.get_by_label(&format!(
        "current pose: ({:.3}, {:.3}, {:.3})",
        p.x, p.y, p.z
    ));

    harness.get_by_label("<").click();
    harness.run();
    harness.get_by_label("frame 3 / 6");
    assert_eq!(
        harness.state().session.marker(),
        Some(ground_truth.poses[3])
    );
}

#[test]
fn main_window_matches_its_snapshot() {
    let options = ViewOptions {
        source: ViewSource::Scene(Box::new(scene_job(4))),
        spec: PerturbSpec::parse("fog:2,gaussian_noise:1@dynamic,depth_missing:3,misalign:1")
            .unwrap(),
        seed: 7,
        estimate: None,
    };
    let mut harness = harness(&options);
    harness.get_by_label(">").click();
    harness.run();
    // The adapter's name and driver version differ between machines.
    let gpu = harness.get_by_label_contains("GPU:").rect();
    harness.mask(gpu);
    // Lavapipe renders the same pixels on every run; the tolerance absorbs font hinting and
    // driver rounding on other machines, not a moved widget.
    let tolerance = SnapshotOptions::new().threshold(2.0).max_failed_pixels(40);
    harness.snapshot_options("main_window", &tolerance);
}

#[test]
fn an_unreadable_dataset_and_a_bad_spec_show_as_one_line_in_the_window() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("notes.txt"), "not a dataset").unwrap();
    let options = ViewOptions {
        source: ViewSource::Dataset(dir.path().to_path_buf()),
        spec: PerturbSpec::default(),
        seed: 0,
        estimate: None,
    };
    let harness = harness(&options);
    let error = harness.state().session.error.clone().unwrap();
    assert!(error.contains(&dir.path().display().to_string()), "{error}");
    harness.get_by_label_contains("error: ");
    harness.get_by_label("nothing to show (see the error above)");

    let options = ViewOptions {
        source: ViewSource::Scene(Box::new(scene_job(2))),
        spec: PerturbSpec::parse("fog:2").unwrap(),
        seed: 0,
        estimate: None,
    };
    let mut harness = self::harness(&options);
    let field = harness.get_by_label("type a spec");
    field.focus();
    field.type_text(",fogg:9");
    harness.run();
    harness.get_by_label("apply").click();
    harness.run();
    let error = harness.state().session.error.clone().unwrap();
    assert!(error.contains("fogg"), "{error}");
    harness.get_by_label_contains("error: spec:");
    assert_eq!(
        harness.state().session.spec_string(),
        "fog:2",
        "the shown spec stays"
    );
}
