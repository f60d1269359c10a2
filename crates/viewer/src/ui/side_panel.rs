//! The right panel: trajectory, free camera (scenes), export.

use std::path::PathBuf;

use crate::app::ViewerApp;

pub(crate) fn side_panel(ui: &mut egui::Ui, app: &mut ViewerApp) {
    egui::Panel::right("side")
        .default_size(300.0)
        .show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                ui.heading("Trajectory");
                super::trajectory_panel::trajectory_panel(ui, app);
                let is_scene = app.session.sequence.as_ref().is_some_and(|s| s.is_scene());
                if is_scene {
                    ui.separator();
                    free_camera(ui, app);
                }
                ui.separator();
                export(ui, app);
            });
        });
}

fn free_camera(ui: &mut egui::Ui, app: &mut ViewerApp) {
    ui.heading("Free camera");
    let mut active = app.session.camera.active;
    ui.checkbox(&mut active, "fly (W A S D, Q E, arrows, drag)");
    app.session.set_free_camera(active);
    ui.horizontal(|ui| {
        ui.label("speed");
        ui.add(
            egui::DragValue::new(&mut app.session.camera.speed)
                .speed(0.05)
                .range(0.05..=20.0)
                .suffix(" m/s"),
        );
        if ui
            .button("snap back")
            .on_hover_text("to the current frame's pose")
            .clicked()
        {
            app.session.snap_back();
        }
    });
    ui.horizontal(|ui| {
        if ui.button("add pose").clicked() {
            app.session.camera.record();
        }
        ui.label(format!("{} poses", app.session.camera.recorded.len()));
        if ui.button("clear").clicked() {
            app.session.camera.recorded.clear();
        }
    });
    ui.horizontal(|ui| {
        let label = ui.label("path");
        ui.add(egui::TextEdit::singleline(&mut app.panels.camera_path).desired_width(130.0))
            .labelled_by(label.id);
        if ui.button("save traj.txt").clicked() {
            let path = PathBuf::from(&app.panels.camera_path);
            app.session.save_camera_path(&path);
        }
    });
}

fn export(ui: &mut egui::Ui, app: &mut ViewerApp) {
    ui.heading("Export");
    ui.horizontal(|ui| {
        let label = ui.label("folder");
        ui.add(egui::TextEdit::singleline(&mut app.panels.export_dir).desired_width(180.0))
            .labelled_by(label.id);
    });
    let dir = PathBuf::from(&app.panels.export_dir);
    ui.horizontal(|ui| {
        if ui
            .button("export frame")
            .on_hover_text("colour and depth PNGs of this frame")
            .clicked()
        {
            if let Err(e) = app.session.export_frame(&dir) {
                app.session.error = Some(e.to_string());
            }
        }
    });
    ui.horizontal(|ui| {
        if ui.button("export clip").clicked() {
            let count = app.panels.clip_frames;
            if let Err(e) = app.session.export_clip(&dir, count) {
                app.session.error = Some(e.to_string());
            }
        }
        let count = ui.add(egui::DragValue::new(&mut app.panels.clip_frames).range(1..=1000));
        let label = ui.label("frames from here");
        count.labelled_by(label.id);
    });
}
