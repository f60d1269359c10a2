//! The frame panel: RGB and colour-mapped depth, side by side or stacked, each split between
//! clean (left of the split) and perturbed; scroll zooms, drag pans (or turns the free camera),
//! the pixel under the cursor is read out; a legend gives the depth colours in metres.

use rslam_pipeline::depth_colormap::depth_color;

use crate::app::{FrameTextureIds, FrameView, ViewerApp};

pub(crate) fn frame_panel(ui: &mut egui::Ui, app: &mut ViewerApp) {
    egui::CentralPanel::default().show(ui, |ui| {
        ui.horizontal(|ui| {
            ui.add(
                egui::Slider::new(&mut app.view.split, 0.0..=1.0)
                    .text("split clean | perturbed")
                    .show_value(false),
            );
            ui.checkbox(&mut app.view.stacked, "stacked");
            ui.label(format!("zoom {:.1}×", app.view.zoom));
            if ui.button("fit").clicked() {
                app.view.zoom = 1.0;
                app.view.center = egui::vec2(0.5, 0.5);
            }
        });
        depth_legend(ui, app);
        readout_line(ui, app);
        let Some(textures) = app.textures() else {
            ui.centered_and_justified(|ui| {
                ui.label(if app.session.error.is_some() {
                    "nothing to show (see the error above)"
                } else {
                    "loading…"
                })
            });
            return;
        };
        let ids = FrameIds::of(textures);
        let size = textures.size;
        let has_depth = app.session.shown().is_some_and(|s| s.has_depth());
        let area = ui.available_rect_before_wrap();
        let count = if has_depth { 2.0 } else { 1.0 };
        let cell = if app.view.stacked {
            egui::vec2(area.width(), area.height() / count)
        } else {
            egui::vec2(area.width() / count, area.height())
        };
        let mut images = vec![(ids.color, area.min)];
        if has_depth {
            let offset = if app.view.stacked {
                egui::vec2(0.0, cell.y)
            } else {
                egui::vec2(cell.x, 0.0)
            };
            images.push((ids.depth, area.min + offset));
        }
        app.panels.frame_rects.clear();
        for ((clean, perturbed), corner) in images {
            let rect = fit(egui::Rect::from_min_size(corner, cell), size);
            app.panels.frame_rects.push(rect);
            let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
            draw_split(ui, &app.view, rect, clean, perturbed);
            handle_input(ui, app, &response, rect, size);
        }
    });
}

struct FrameIds {
    color: (egui::TextureId, egui::TextureId),
    depth: (egui::TextureId, egui::TextureId),
}

impl FrameIds {
    fn of(t: &FrameTextureIds) -> Self {
        Self {
            color: (t.clean_color, t.perturbed_color),
            depth: (t.clean_depth, t.perturbed_depth),
        }
    }
}

/// The largest rect of the image's aspect centred in `cell`.
fn fit(cell: egui::Rect, (w, h): (u32, u32)) -> egui::Rect {
    let scale = (cell.width() / w as f32).min(cell.height() / h as f32);
    egui::Rect::from_center_size(cell.center(), egui::vec2(w as f32, h as f32) * scale)
}

/// The image's uv rect under the current zoom and pan.
fn visible_uv(view: &FrameView) -> egui::Rect {
    let half = 0.5 / view.zoom;
    egui::Rect::from_center_size(view.center.to_pos2(), egui::vec2(2.0 * half, 2.0 * half))
}

fn draw_split(
    ui: &egui::Ui,
    view: &FrameView,
    rect: egui::Rect,
    clean: egui::TextureId,
    perturbed: egui::TextureId,
) {
    let uv = visible_uv(view);
    let painter = ui.painter_at(rect);
    let x = rect.left() + view.split * rect.width();
    let u = uv.left() + view.split * uv.width();
    let white = egui::Color32::WHITE;
    let left = egui::Rect::from_min_max(rect.min, egui::pos2(x, rect.bottom()));
    let left_uv = egui::Rect::from_min_max(uv.min, egui::pos2(u, uv.bottom()));
    painter.image(clean, left, left_uv, white);
    let right = egui::Rect::from_min_max(egui::pos2(x, rect.top()), rect.max);
    let right_uv = egui::Rect::from_min_max(egui::pos2(u, uv.top()), uv.max);
    painter.image(perturbed, right, right_uv, white);
    if view.split > 0.0 && view.split < 1.0 {
        painter.line_segment(
            [egui::pos2(x, rect.top()), egui::pos2(x, rect.bottom())],
            egui::Stroke::new(1.5, egui::Color32::YELLOW),
        );
    }
}

fn handle_input(
    ui: &egui::Ui,
    app: &mut ViewerApp,
    response: &egui::Response,
    rect: egui::Rect,
    (w, h): (u32, u32),
) {
    let uv = visible_uv(&app.view);
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            app.view.zoom = (app.view.zoom * (scroll / 200.0).exp()).clamp(1.0, 64.0);
        }
    }
    if response.dragged() {
        let delta = response.drag_delta();
        if app.session.camera.active {
            app.session.fly(crate::free_camera::CameraStep {
                yaw: delta.x as f64 * 0.005,
                pitch: -delta.y as f64 * 0.005,
                ..Default::default()
            });
        } else {
            app.view.center -= egui::vec2(
                delta.x / rect.width() * uv.width(),
                delta.y / rect.height() * uv.height(),
            );
        }
    }
    let half = 0.5 / app.view.zoom;
    app.view.center = app
        .view
        .center
        .clamp(egui::vec2(half, half), egui::vec2(1.0 - half, 1.0 - half));
    let Some(pointer) = response.hover_pos() else {
        return;
    };
    let at = uv.min + (pointer - rect.min) / rect.size() * uv.size();
    let (x, y) = ((at.x * w as f32) as u32, (at.y * h as f32) as u32);
    let moved = app.panels.readout.map(|(px, py, _)| (px, py)) != Some((x, y));
    let changed = ui.input(|i| i.pointer.is_moving()) || moved || app.session.playback.playing;
    if changed {
        app.panels.readout = app.session.pixel(x, y).map(|r| (x, y, r));
    }
}

fn readout_line(ui: &mut egui::Ui, app: &ViewerApp) {
    let text = match app.panels.readout {
        Some((x, y, r)) => {
            let [cr, cg, cb] = r.clean_rgb;
            let [pr, pg, pb] = r.perturbed_rgb;
            format!(
                "pixel ({x}, {y}): clean RGB {cr} {cg} {cb}, depth {:.3} m · perturbed RGB {pr} {pg} {pb}, depth {:.3} m",
                r.clean_depth, r.perturbed_depth
            )
        }
        None => "pixel: hover over the frame".to_string(),
    };
    ui.monospace(text);
}

/// The Turbo scale from near to far with ticks in metres (colours from the shader's CPU twin).
fn depth_legend(ui: &mut egui::Ui, app: &mut ViewerApp) {
    ui.horizontal(|ui| {
        let mut range = app.session.depth_range;
        ui.label("depth");
        ui.add(
            egui::DragValue::new(&mut range.near)
                .speed(0.05)
                .range(0.0..=100.0)
                .suffix(" m"),
        );
        let (rect, _) = ui.allocate_exact_size(egui::vec2(220.0, 16.0), egui::Sense::hover());
        let painter = ui.painter_at(rect);
        let steps = 64;
        for i in 0..steps {
            let t = (i as f32 + 0.5) / steps as f32;
            let z = range.near + t * (range.far - range.near);
            let [r, g, b] = depth_color(z.max(1e-6), range);
            let x0 = rect.left() + rect.width() * i as f32 / steps as f32;
            let x1 = rect.left() + rect.width() * (i + 1) as f32 / steps as f32;
            let cell = egui::Rect::from_min_max(
                egui::pos2(x0, rect.top()),
                egui::pos2(x1 + 0.5, rect.bottom()),
            );
            painter.rect_filled(cell, 0.0, egui::Color32::from_rgb(r, g, b));
        }
        let mid = 0.5 * (range.near + range.far);
        painter.text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            format!("{mid:.1} m"),
            egui::FontId::monospace(10.0),
            egui::Color32::BLACK,
        );
        ui.add(
            egui::DragValue::new(&mut range.far)
                .speed(0.05)
                .range(0.1..=100.0)
                .suffix(" m"),
        );
        ui.weak("black: no depth");
        app.session.set_depth_range(range);
    });
}
