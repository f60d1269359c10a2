//! The native window: eframe on the session's own wgpu device, so that the textures the pipeline
//! leaves on the GPU are sampled where they lie.

use std::path::PathBuf;

use rslam_gpu::GpuContext;

use crate::app::ViewerApp;
use crate::session::{Session, ViewOptions};
use crate::ViewerError;

#[derive(Clone, Debug)]
pub struct WindowOptions {
    /// Inner size in points.
    pub size: [f32; 2],
    /// Save a screenshot here once the first frame is shown, then close.
    pub screenshot: Option<PathBuf>,
}

impl Default for WindowOptions {
    fn default() -> Self {
        Self {
            size: [1600.0, 900.0],
            screenshot: None,
        }
    }
}

/// egui-wgpu's setup on `ctx`'s instance, adapter, device and queue.
fn existing_setup(ctx: &GpuContext) -> egui_wgpu::WgpuSetup {
    egui_wgpu::WgpuSetup::Existing(egui_wgpu::WgpuSetupExisting {
        instance: ctx.instance.clone(),
        adapter: ctx.adapter.clone(),
        device: ctx.device.clone(),
        queue: ctx.queue.clone(),
    })
}

/// An egui-wgpu render state on `ctx`'s device without a window (tests, measurements).
pub fn render_state_for(ctx: &GpuContext) -> Result<egui_wgpu::RenderState, ViewerError> {
    let config = egui_wgpu::WgpuConfiguration {
        wgpu_setup: existing_setup(ctx),
        ..Default::default()
    };
    pollster::block_on(egui_wgpu::RenderState::create(
        &config,
        &ctx.instance,
        None,
        egui_wgpu::RendererOptions::PREDICTABLE,
    ))
    .map_err(|e| ViewerError::Window {
        message: e.to_string(),
    })
}

struct WindowApp(ViewerApp);

impl eframe::App for WindowApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.0.ui(ui);
    }
}

/// Opens the window on `ctx` and runs until it is closed. Whatever cannot be opened is shown in
/// the window; the error returned is the window's own (no display, no surface).
pub fn run_window(
    ctx: GpuContext,
    view: ViewOptions,
    window: WindowOptions,
) -> Result<(), ViewerError> {
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_inner_size(window.size)
            .with_title("rslam view"),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options: egui_wgpu::WgpuConfiguration {
            wgpu_setup: existing_setup(&ctx),
            ..Default::default()
        },
        ..Default::default()
    };
    let screenshot = window.screenshot.clone();
    eframe::run_native(
        "rslam view",
        native,
        Box::new(move |cc| {
            let render_state = cc
                .wgpu_render_state
                .clone()
                .ok_or("eframe started without its wgpu renderer")?;
            let session = Session::open(ctx, &view);
            if let Some(error) = &session.error {
                eprintln!("error: {error}");
            }
            let mut app = ViewerApp::new(session, render_state);
            if let Some(path) = screenshot {
                app = app.screenshot_then_close(path);
            }
            Ok(Box::new(WindowApp(app)))
        }),
    )
    .map_err(|e| ViewerError::Window {
        message: e.to_string(),
    })
}
