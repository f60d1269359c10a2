//! Keys of the free camera: W/S forward and back, A/D left and right, Q/E up and down, arrows
//! turn; Shift flies five times faster. Ignored while a text field has the keyboard.

use crate::free_camera::CameraStep;
use crate::session::Session;

/// Radians per second of a held arrow key.
const TURN_RATE: f64 = 1.2;

pub(crate) fn camera_keys(ui: &egui::Ui, session: &mut Session, dt: f64) {
    if !session.camera.active || ui.ctx().egui_wants_keyboard_input() {
        return;
    }
    let step = ui.input(|i| {
        let axis = |plus: egui::Key, minus: egui::Key| {
            (i.key_down(plus) as i32 - i.key_down(minus) as i32) as f64
        };
        let boost = if i.modifiers.shift { 5.0 } else { 1.0 };
        let metres = session.camera.speed * boost * dt;
        CameraStep {
            right: axis(egui::Key::D, egui::Key::A) * metres,
            down: axis(egui::Key::E, egui::Key::Q) * metres,
            forward: axis(egui::Key::W, egui::Key::S) * metres,
            yaw: axis(egui::Key::ArrowRight, egui::Key::ArrowLeft) * TURN_RATE * dt,
            pitch: axis(egui::Key::ArrowUp, egui::Key::ArrowDown) * TURN_RATE * dt,
        }
    });
    if !step.is_still() {
        session.fly(step);
        ui.ctx().request_repaint();
    }
}
