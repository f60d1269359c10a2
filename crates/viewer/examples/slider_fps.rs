//! Frames per second of the viewer while a severity slider is dragged, with fog and
//! gaussian_noise on 1200×680 frames (the Replica camera): each frame the slider moves to another
//! severity, the pipeline re-perturbs the frame on the GPU and egui-wgpu paints the whole window.
//! Printed, never asserted. Run: `cargo run --release -p rslam-viewer --example slider_fps`.
//!
//! The window is rendered offscreen by egui_kittest's wgpu renderer, which also reads each frame
//! back to the CPU; a real window presents instead, so the figure is a lower bound.

use std::time::Instant;

use egui::accesskit::Role;
use egui_kittest::kittest::Queryable;
use egui_kittest::{wgpu::WgpuTestRenderer, Harness};
use rslam_core::Intrinsics;
use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_perturb::PerturbSpec;
use rslam_pipeline::SceneJob;
use rslam_viewer::{render_state_for, ItemSetting, Session, ViewOptions, ViewSource, ViewerApp};

const FRAMES: usize = 40;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let ctx = GpuContext::new(&AdapterChoice::default())?;
    let device = ctx.describe();
    let render_state = render_state_for(&ctx)?;
    let spec = PerturbSpec::parse("fog:3,gaussian_noise:3")?;
    let options = ViewOptions {
        source: ViewSource::Scene(Box::new(SceneJob {
            scene: "room0".into(),
            trajectory: None,
            frames: Some(10),
            camera: Intrinsics::parse("replica")?,
            rate_hz: 20.0,
            spec: spec.clone(),
            seed: 0,
            agent: None,
            capture: Default::default(),
            actor_files: Vec::new(),
        })),
        spec,
        seed: 0,
        estimate: None,
    };
    let session = Session::open(ctx, &options);
    if let Some(error) = &session.error {
        return Err(error.clone().into());
    }
    let app = ViewerApp::new(session, render_state.clone());
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1600.0, 900.0))
        .renderer(WgpuTestRenderer::from_render_state(render_state))
        .build_ui_state(|ui, app: &mut ViewerApp| app.ui(ui), app);
    harness.run();
    harness.render()?;

    let shows_before = harness.state().session.shows;
    let start = Instant::now();
    for i in 0..FRAMES {
        let severity = [1.0, 2.0, 3.0, 4.0, 5.0, 4.0, 3.0, 2.0][i % 8];
        harness
            .get_by_role_and_label(Role::Slider, "fog severity")
            .set_value_accesskit(severity);
        harness.step();
        harness.render()?;
    }
    let seconds = start.elapsed().as_secs_f64();
    let shows = harness.state().session.shows - shows_before;
    // The same severity changes without the window: what the pipeline's part costs.
    let session = &mut harness.state_mut().session;
    let start = Instant::now();
    for i in 0..FRAMES {
        let severity = [1, 2, 3, 4, 5, 4, 3, 2][i % 8];
        session.editor.items[0].setting = ItemSetting::Severity {
            severity: rslam_perturb::Severity::whole(severity).expect("a severity 1..=5"),
            dynamic: false,
        };
        session.apply_editor();
        session.refresh();
        session.ctx.wait_idle()?;
    }
    let pipeline_seconds = start.elapsed().as_secs_f64();
    println!("device: {device}");
    println!(
        "re-perturbing and colour-mapping the shown frame alone: {:.1} frames/s ({:.1} ms per frame)",
        FRAMES as f64 / pipeline_seconds,
        1000.0 * pipeline_seconds / FRAMES as f64
    );
    println!(
        "dragging the fog severity slider (fog + gaussian_noise, 1200x680 frames, 1600x900 window): \
         {FRAMES} window frames, {shows} perturbed frames shown, {:.1} fps ({:.1} ms per frame)",
        FRAMES as f64 / seconds,
        1000.0 * seconds / FRAMES as f64
    );
    Ok(())
}
