//! The top bar: what is open, the adapter, the last error or notice.

use crate::app::ViewerApp;

pub(crate) fn top_bar(ui: &mut egui::Ui, app: &mut ViewerApp) {
    egui::Panel::top("top bar").show(ui, |ui| {
        ui.horizontal(|ui| {
            let session = &app.session;
            let name = session
                .sequence
                .as_ref()
                .map_or("nothing open", |s| s.name());
            ui.strong(format!("rslam view — {name}"));
            if let Some(sequence) = &session.sequence {
                let (w, h) = sequence.size();
                ui.label(format!("{w}×{h}, {} Hz", sequence.rate_hz()));
            }
            ui.weak(format!("GPU: {}", session.ctx.adapter_info.name));
            if let Some(fps) = app.fps() {
                ui.weak(format!("{fps:.1} fps"));
            }
        });
        if let Some(error) = &app.session.error {
            ui.colored_label(ui.visuals().error_fg_color, format!("error: {error}"));
        } else if let Some(notice) = &app.session.notice {
            ui.label(notice);
        }
    });
}
