//! The timeline: step, play/pause at the sequence rate, scrub; under it each frame corruption's
//! per-frame severity (dynamic specs) and, with `fast`/`misalign`, which source frame each output
//! frame's colour and depth come from.

use crate::app::ViewerApp;

const ROW: f32 = 12.0;

pub(crate) fn timeline(ui: &mut egui::Ui, app: &mut ViewerApp) {
    egui::Panel::bottom("timeline").show(ui, |ui| {
        let len = app.session.len();
        ui.horizontal(|ui| {
            if ui.button("<").on_hover_text("previous frame").clicked() {
                app.session.step(false);
            }
            let playing = app.session.playback.playing;
            let label = if playing { "pause" } else { "play" };
            if ui.button(label).clicked() {
                app.session.playback.playing = !playing;
            }
            if ui.button(">").on_hover_text("next frame").clicked() {
                app.session.step(true);
            }
            let mut index = app.session.index();
            let last = len.saturating_sub(1);
            ui.spacing_mut().slider_width = (ui.available_width() - 260.0).max(100.0);
            ui.add_enabled(
                len > 0,
                egui::Slider::new(&mut index, 0..=last)
                    .text("scrub")
                    .show_value(false),
            );
            app.session.set_index(index);
            let time = app
                .session
                .sequence
                .as_ref()
                .and_then(|s| s.plan().frames.get(app.session.index()))
                .map_or(0.0, |f| f.rgb_time);
            ui.monospace(format!("frame {} / {len}", app.session.index()))
                .on_hover_text("output frame index (from 0) / output frames");
            ui.monospace(format!("t = {time:.3} s"));
        });
        strips(ui, app);
    });
}

/// Severity rows and the frame mapping, painted; a click scrubs.
fn strips(ui: &mut egui::Ui, app: &mut ViewerApp) {
    let Some(sequence) = &app.session.sequence else {
        return;
    };
    let plan = sequence.plan();
    let len = plan.len();
    if len == 0 {
        return;
    }
    let dynamic: Vec<_> = plan.severities.iter().collect();
    let spec = app.session.applied_spec();
    let mapping = spec.fast.is_some() || spec.misalign.is_some();
    let rows = dynamic.len() as f32 + if mapping { 3.0 } else { 0.0 };
    if rows == 0.0 {
        return;
    }
    let label_width = 110.0;
    let (rect, response) = ui.allocate_exact_size(
        egui::vec2(ui.available_width(), rows * ROW + 4.0),
        egui::Sense::click_and_drag(),
    );
    let painter = ui.painter_at(rect);
    let strip = egui::Rect::from_min_max(rect.min + egui::vec2(label_width, 0.0), rect.max);
    let x_of = |j: f32| strip.left() + strip.width() * (j + 0.5) / len as f32;
    let text_color = ui.visuals().text_color();
    let font = egui::FontId::monospace(10.0);
    let mut y = rect.top();
    for item in &dynamic {
        painter.text(
            egui::pos2(rect.left(), y + ROW / 2.0),
            egui::Align2::LEFT_CENTER,
            &item.item,
            font.clone(),
            text_color,
        );
        let step = strip.width() / len as f32;
        for (j, severity) in item.values().unwrap_or_default().into_iter().enumerate() {
            let s = severity as f32 / 5.0;
            let shade = egui::Color32::from_rgb(
                (40.0 + 215.0 * s) as u8,
                (60.0 * (1.0 - s)) as u8 + 40,
                60,
            );
            let x = x_of(j as f32) - step / 2.0;
            let cell = egui::Rect::from_min_size(
                egui::pos2(x, y + 1.0),
                egui::vec2(step.max(1.0), ROW - 2.0),
            );
            painter.rect_filled(cell, 0.0, shade);
        }
        y += ROW;
    }
    if mapping {
        // Output frames on the upper line, source frames on the lower; lines join each output
        // frame to its colour source (white) and its depth source (cyan).
        let sources = plan
            .rgb_source
            .iter()
            .chain(&plan.depth_source)
            .copied()
            .max()
            .unwrap_or(0)
            + 1;
        let xs = |s: usize| strip.left() + strip.width() * (s as f32 + 0.5) / sources as f32;
        let (top, bottom) = (y + 2.0, y + 3.0 * ROW - 2.0);
        painter.text(
            egui::pos2(rect.left(), top + 4.0),
            egui::Align2::LEFT_CENTER,
            "output frame",
            font.clone(),
            text_color,
        );
        painter.text(
            egui::pos2(rect.left(), bottom - 4.0),
            egui::Align2::LEFT_CENTER,
            "source frame",
            font.clone(),
            text_color,
        );
        let every = (len / 400).max(1);
        for j in (0..len).step_by(every) {
            let strong = j == app.session.index();
            let width = if strong { 2.0 } else { 0.5 };
            let top_point = egui::pos2(x_of(j as f32), top);
            painter.line_segment(
                [top_point, egui::pos2(xs(plan.rgb_source[j]), bottom)],
                egui::Stroke::new(
                    width,
                    egui::Color32::from_white_alpha(if strong { 255 } else { 90 }),
                ),
            );
            if let Some(&d) = plan.depth_source.get(j) {
                painter.line_segment(
                    [top_point, egui::pos2(xs(d), bottom)],
                    egui::Stroke::new(
                        width,
                        egui::Color32::from_rgba_unmultiplied(
                            0,
                            220,
                            255,
                            if strong { 255 } else { 90 },
                        ),
                    ),
                );
            }
        }
    }
    let cursor = x_of(app.session.index() as f32);
    painter.line_segment(
        [
            egui::pos2(cursor, rect.top()),
            egui::pos2(cursor, rect.bottom()),
        ],
        egui::Stroke::new(1.5, egui::Color32::YELLOW),
    );
    if let Some(pos) = response.interact_pointer_pos() {
        if response.clicked() || response.dragged() {
            let j = ((pos.x - strip.left()) / strip.width() * len as f32).floor();
            app.session.set_index(j.max(0.0) as usize);
        }
    }
}
