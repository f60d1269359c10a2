//! The trajectory panel: top and side views of the ground truth; with `--estimate` the aligned
//! estimate, each pose coloured by its error, and the ATE; the current frame (and the free
//! camera) marked.

use glam::DVec3;

use crate::app::ViewerApp;

/// Which world axis points up; the top view drops it, the side view keeps it vertical.
fn up_axis(points: &[DVec3]) -> usize {
    let (min, max) = bounds(points);
    let extent = max - min;
    let extents = [extent.x, extent.y, extent.z];
    (0..3)
        .min_by(|&a, &b| extents[a].total_cmp(&extents[b]))
        .unwrap_or(1)
}

fn bounds(points: &[DVec3]) -> (DVec3, DVec3) {
    points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    )
}

pub(crate) fn trajectory_panel(ui: &mut egui::Ui, app: &ViewerApp) {
    let view = &app.session.trajectory;
    let gt: Vec<DVec3> = view
        .ground_truth
        .poses
        .iter()
        .map(|p| p.translation)
        .collect();
    if gt.is_empty() {
        ui.weak("no ground truth");
        return;
    }
    let mut all = gt.clone();
    if let Some(est) = &view.estimate {
        all.extend(&est.aligned);
    }
    let up = up_axis(&gt);
    let horizontal: Vec<usize> = (0..3).filter(|&a| a != up).collect();
    let marker = app.session.marker().map(|p| p.translation);
    if let Some(p) = marker {
        ui.monospace(format!(
            "current pose: ({:.3}, {:.3}, {:.3})",
            p.x, p.y, p.z
        ));
    }
    if let Some(est) = &view.estimate {
        ui.label(format!(
            "ATE RMSE {:.4} m over {} poses (max {:.4} m)",
            est.ate_rmse,
            est.errors.len(),
            est.max_error
        ));
    }
    let free = app
        .session
        .camera
        .active
        .then_some(app.session.camera.world_from_camera.translation);
    let axes_name = ["x", "y", "z"];
    for (title, axes) in [
        ("top", [horizontal[0], horizontal[1]]),
        ("side", [horizontal[0], up]),
    ] {
        ui.weak(format!(
            "{title} view ({}, {})",
            axes_name[axes[0]], axes_name[axes[1]]
        ));
        let size = egui::vec2(ui.available_width(), 150.0);
        let (rect, _) = ui.allocate_exact_size(size, egui::Sense::hover());
        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 2.0, egui::Color32::from_gray(20));
        let (lo, hi) = bounds(&all);
        let (lo, hi) = ([lo[axes[0]], lo[axes[1]]], [hi[axes[0]], hi[axes[1]]]);
        let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-6);
        let scale = (rect.width().min(rect.height()) - 16.0) as f64 / span;
        let centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
        // Side view: up is the axis with the least spread; image y grows downward, so a
        // y-down world (camera convention) reads right way up when the axis is drawn as is.
        let to_screen = |p: DVec3| {
            egui::pos2(
                rect.center().x + ((p[axes[0]] - centre[0]) * scale) as f32,
                rect.center().y + ((p[axes[1]] - centre[1]) * scale) as f32,
            )
        };
        let line: Vec<egui::Pos2> = gt.iter().map(|&p| to_screen(p)).collect();
        painter.add(egui::Shape::line(
            line,
            egui::Stroke::new(1.0, egui::Color32::from_gray(200)),
        ));
        if let Some(est) = &view.estimate {
            for (p, e) in est.aligned.iter().zip(&est.errors) {
                let t = (e / est.max_error.max(1e-12)) as f32;
                let color =
                    egui::Color32::from_rgb((255.0 * t) as u8, (255.0 * (1.0 - t)) as u8, 40);
                painter.circle_filled(to_screen(*p), 1.8, color);
            }
        }
        if let Some(p) = free {
            painter.circle_stroke(
                to_screen(p),
                5.0,
                egui::Stroke::new(2.0, egui::Color32::YELLOW),
            );
        }
        if let Some(p) = marker {
            painter.circle_filled(to_screen(p), 4.0, egui::Color32::RED);
        }
    }
    if view.estimate.is_some() {
        ui.weak("estimate: green = small error, red = the largest");
    }
}
