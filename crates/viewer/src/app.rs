//! The window: a [`Session`] drawn by egui. Panels draw the session and turn input into calls on
//! it; the shown frame's textures are registered with egui-wgpu once and sampled where they lie.

use std::path::PathBuf;
use std::sync::mpsc;
use std::sync::Arc;

use egui_wgpu::wgpu;

use crate::session::Session;
use crate::ui;

/// The shown frame's textures as egui sees them.
pub(crate) struct FrameTextureIds {
    pub clean_color: egui::TextureId,
    pub perturbed_color: egui::TextureId,
    pub clean_depth: egui::TextureId,
    pub perturbed_depth: egui::TextureId,
    pub size: (u32, u32),
}

/// How the frame panel shows the frame.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameView {
    /// Where clean ends and perturbed begins, as a fraction of the image width.
    pub split: f32,
    /// Magnification; 1 = whole image.
    pub zoom: f32,
    /// The image point (0..1) at the view's centre.
    pub center: egui::Vec2,
    /// RGB above depth instead of side by side.
    pub stacked: bool,
}

impl Default for FrameView {
    fn default() -> Self {
        Self {
            split: 0.5,
            zoom: 1.0,
            center: egui::vec2(0.5, 0.5),
            stacked: false,
        }
    }
}

/// Text fields and other state of the panels that is not the session's.
pub(crate) struct PanelState {
    pub typed_spec: String,
    pub export_dir: String,
    pub clip_frames: usize,
    pub camera_path: String,
    pub readout: Option<(u32, u32, rslam_pipeline::PixelReadout)>,
    pub frame_times: std::collections::VecDeque<f64>,
    /// Where the frame panel drew its images this frame (colour, then depth).
    pub frame_rects: Vec<egui::Rect>,
}

pub struct ViewerApp {
    pub session: Session,
    pub view: FrameView,
    pub(crate) panels: PanelState,
    render_state: egui_wgpu::RenderState,
    textures: Option<FrameTextureIds>,
    screenshot: Option<Screenshot>,
}

/// `--screenshot PATH`: once the frame is up, the window is captured, saved and closed.
struct Screenshot {
    path: PathBuf,
    frames_to_wait: u32,
    receiver: Option<mpsc::Receiver<Arc<egui::ColorImage>>>,
}

impl ViewerApp {
    /// `render_state` must be on the session's device (eframe given the session's device, or a
    /// test harness built from it).
    pub fn new(session: Session, render_state: egui_wgpu::RenderState) -> Self {
        let typed_spec = session.spec_string();
        Self {
            session,
            view: FrameView::default(),
            panels: PanelState {
                typed_spec,
                export_dir: "rslam-export".into(),
                clip_frames: 20,
                camera_path: "traj.txt".into(),
                readout: None,
                frame_times: Default::default(),
                frame_rects: Vec::new(),
            },
            render_state,
            textures: None,
            screenshot: None,
        }
    }

    /// Saves a screenshot of the window to `path` once the frame is shown, then closes it.
    pub fn screenshot_then_close(mut self, path: PathBuf) -> Self {
        self.screenshot = Some(Screenshot {
            path,
            frames_to_wait: 3,
            receiver: None,
        });
        self
    }

    /// Frames per second of the window over its last frames.
    pub fn fps(&self) -> Option<f64> {
        let times = &self.panels.frame_times;
        let (first, last) = (times.front()?, times.back()?);
        (times.len() > 1 && last > first).then(|| (times.len() - 1) as f64 / (last - first))
    }

    /// One frame of the window.
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        let (dt, now) = ui.input(|i| (i.stable_dt as f64, i.time));
        self.panels.frame_times.push_back(now);
        while self.panels.frame_times.len() > 30 {
            self.panels.frame_times.pop_front();
        }
        self.session.tick(dt);
        ui::camera_keys(ui, &mut self.session, dt);

        ui::top_bar(ui, self);
        ui::timeline(ui, self);
        ui::perturbation_panel(ui, self);
        ui::side_panel(ui, self);
        ui::frame_panel(ui, self);

        // The frame goes onto the GPU after the panels took this frame's input: the textures
        // are sampled when egui paints, after this, so what is drawn is already the new frame.
        let error = self.session.error.clone();
        let shown = self.session.refresh();
        let registered = self.register_textures();
        if self.session.playback.playing || registered || (shown && self.session.error != error) {
            ui.ctx().request_repaint();
        }
        self.take_screenshot(ui.ctx());
    }

    /// Where the frame panel drew its images in the last frame (colour, then depth), in points.
    pub fn frame_rects(&self) -> &[egui::Rect] {
        &self.panels.frame_rects
    }

    pub(crate) fn textures(&self) -> Option<&FrameTextureIds> {
        self.textures.as_ref()
    }

    /// Registers the shown frame's textures with egui-wgpu when they are new; says whether it did.
    fn register_textures(&mut self) -> bool {
        let Some(shown) = self.session.shown() else {
            return false;
        };
        if self.textures.as_ref().map(|t| t.size) == Some(shown.size()) {
            return false;
        }
        let mut renderer = self.render_state.renderer.write();
        if let Some(old) = self.textures.take() {
            for id in [
                old.clean_color,
                old.perturbed_color,
                old.clean_depth,
                old.perturbed_depth,
            ] {
                renderer.free_texture(&id);
            }
        }
        let device = &self.render_state.device;
        let views = shown.views();
        let mut register = |view: &wgpu::TextureView| {
            renderer.register_native_texture(device, view, wgpu::FilterMode::Nearest)
        };
        self.textures = Some(FrameTextureIds {
            clean_color: register(&views.clean_color),
            perturbed_color: register(&views.perturbed_color),
            clean_depth: register(&views.clean_depth),
            perturbed_depth: register(&views.perturbed_depth),
            size: shown.size(),
        });
        true
    }

    fn take_screenshot(&mut self, ctx: &egui::Context) {
        let Some(shot) = &mut self.screenshot else {
            return;
        };
        if let Some(receiver) = &shot.receiver {
            if let Ok(image) = receiver.try_recv() {
                match crate::screenshot::save(&image, &shot.path) {
                    Ok(()) => eprintln!("screenshot: {}", shot.path.display()),
                    Err(e) => eprintln!("error: {e}"),
                }
                self.screenshot = None;
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
            ctx.request_repaint();
            return;
        }
        let ready = self.session.shown().is_some() || self.session.error.is_some();
        if ready {
            shot.frames_to_wait = shot.frames_to_wait.saturating_sub(1);
        }
        if ready && shot.frames_to_wait == 0 {
            let (sender, receiver) = mpsc::channel();
            ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(
                egui::ScreenshotCallback::new(move |image| {
                    let _ = sender.send(image);
                }),
            ));
            shot.receiver = Some(receiver);
        }
        ctx.request_repaint();
    }
}
