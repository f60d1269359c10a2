//! The perturbation panel, built from the catalogue: add, remove and reorder items, a severity
//! slider (or the explicit parameters) per item, static or dynamic, the path and stream items,
//! the seed; the spec string of the shown frame, copyable, and a field to type one.

use rslam_perturb::light::{Daylight, Flicker, LightSpec, Switching};
use rslam_perturb::world::{MovingObjects, Walkers};
use rslam_perturb::{find, Severity};

use crate::app::ViewerApp;
use crate::spec_editor::{DeviationSetting, ItemSetting};

pub(crate) fn perturbation_panel(ui: &mut egui::Ui, app: &mut ViewerApp) {
    egui::Panel::left("perturbations")
        .default_size(310.0)
        .show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                ui.heading("Perturbations");
                spec_line(ui, app);
                ui.separator();
                let before = app.session.editor.clone();
                add_menu(ui, app);
                items(ui, app);
                ui.separator();
                stream_items(ui, app);
                if app.session.editor != before {
                    app.session.apply_editor();
                    app.panels.typed_spec = app.session.spec_string();
                }
                ui.separator();
                let mut seed = app.session.seed;
                ui.horizontal(|ui| {
                    let label = ui.label("seed");
                    ui.add(egui::DragValue::new(&mut seed))
                        .labelled_by(label.id);
                });
                app.session.set_seed(seed);
            });
        });
}

fn spec_line(ui: &mut egui::Ui, app: &mut ViewerApp) {
    let spec = app.session.spec_string();
    ui.horizontal_wrapped(|ui| {
        ui.label("spec:");
        let shown = if spec.is_empty() { "(clean)" } else { &spec };
        ui.add(egui::Label::new(egui::RichText::new(shown).monospace().strong()).selectable(true));
        if ui.button("copy").clicked() {
            ui.ctx().copy_text(spec.clone());
            app.session.notice = Some(format!("copied '{spec}'"));
        }
    });
    ui.horizontal(|ui| {
        let label = ui.label("type a spec");
        let edit = ui
            .add(
                egui::TextEdit::singleline(&mut app.panels.typed_spec)
                    .hint_text("e.g. fog:3,depth_missing:5")
                    .desired_width(180.0),
            )
            .labelled_by(label.id);
        let entered = edit.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        if ui.button("apply").clicked() || entered {
            let text = app.panels.typed_spec.clone();
            app.session.apply_spec_text(&text);
        }
    });
}

fn add_menu(ui: &mut egui::Ui, app: &mut ViewerApp) {
    let mut chosen = None;
    egui::ComboBox::from_label("add perturbation")
        .selected_text("choose…")
        .height(400.0)
        .show_ui(ui, |ui| {
            for name in app.session.editor.addable() {
                let response = ui.selectable_label(false, name);
                let response = match find(name) {
                    Some(entry) => response.on_hover_text(entry.description),
                    None => response,
                };
                if response.clicked() {
                    chosen = Some(name);
                }
            }
        });
    if let Some(name) = chosen {
        app.session.editor.add(name);
    }
}

fn items(ui: &mut egui::Ui, app: &mut ViewerApp) {
    let count = app.session.editor.items.len();
    let mut action = None;
    for index in 0..count {
        let item = &mut app.session.editor.items[index];
        ui.group(|ui| {
            ui.horizontal(|ui| {
                ui.strong(item.name);
                ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                    if ui.small_button("remove").clicked() {
                        action = Some((index, Action::Remove));
                    }
                    if ui
                        .small_button("down")
                        .on_hover_text("apply later")
                        .clicked()
                    {
                        action = Some((index, Action::Down));
                    }
                    if ui
                        .small_button("up")
                        .on_hover_text("apply earlier")
                        .clicked()
                    {
                        action = Some((index, Action::Up));
                    }
                });
            });
            let (example, syntax) = (item.explicit_example(), item.explicit_syntax());
            let name = item.name;
            let real = item.takes_real_severities();
            let mut switch = None;
            match &mut item.setting {
                ItemSetting::Severity { severity, dynamic } => {
                    let mut value = severity.value();
                    let step = if real { 0.05 } else { 1.0 };
                    ui.add(
                        egui::Slider::new(&mut value, 0.0..=5.0)
                            .step_by(step)
                            .text(format!("{name} severity")),
                    );
                    if let Some(picked) = Severity::from_value((value * 100.0).round() / 100.0) {
                        *severity = picked;
                    }
                    ui.horizontal(|ui| {
                        ui.checkbox(dynamic, "dynamic")
                            .on_hover_text("each frame draws its severity from 0 to this one");
                        if let Some(example) = example {
                            if ui.small_button("explicit…").clicked() {
                                switch = Some(ItemSetting::Explicit(example.to_string()));
                            }
                        }
                    });
                }
                ItemSetting::Explicit(text) => {
                    ui.horizontal(|ui| {
                        ui.add(egui::TextEdit::singleline(text).desired_width(120.0));
                        if ui.small_button("severity").clicked() {
                            switch = Some(ItemSetting::Severity {
                                severity: Severity::whole(3).expect("3 is a severity"),
                                dynamic: false,
                            });
                        }
                    });
                    if let Some(syntax) = syntax {
                        ui.weak(syntax);
                    }
                }
            }
            if let Some(setting) = switch {
                item.setting = setting;
            }
            ui.weak(item.parameters());
        });
    }
    let editor = &mut app.session.editor;
    match action {
        Some((i, Action::Remove)) => editor.remove(i),
        Some((i, Action::Up)) => editor.move_item(i, true),
        Some((i, Action::Down)) => editor.move_item(i, false),
        None => {}
    }
}

enum Action {
    Remove,
    Up,
    Down,
}

fn stream_items(ui: &mut egui::Ui, app: &mut ViewerApp) {
    let is_scene = app.session.sequence.as_ref().is_some_and(|s| s.is_scene());
    let editor = &mut app.session.editor;
    if is_scene {
        deviation(ui, "rot (degrees)", &mut editor.rotation, 0.5);
        deviation(ui, "trans (metres)", &mut editor.translation, 0.01);
        light_items(ui, &mut editor.light);
        severity_item(
            ui,
            "actors: people walking through",
            &mut editor.world.actors,
            Walkers::parse,
        );
        severity_item(
            ui,
            "objects: a door swinging, chairs pushed",
            &mut editor.world.objects,
            MovingObjects::parse,
        );
    }
    ui.horizontal(|ui| {
        let mut on = editor.fast.is_some();
        ui.checkbox(&mut on, "fast: keep every K-th frame");
        let mut k = editor.fast.unwrap_or(2);
        if on {
            ui.add(egui::DragValue::new(&mut k).range(1..=50));
        }
        editor.fast = on.then_some(k);
    });
    ui.horizontal(|ui| {
        let mut on = editor.misalign.is_some();
        ui.checkbox(&mut on, "misalign: depth lags");
        let (mut frames, mut dynamic) = editor.misalign.unwrap_or((2, false));
        if on {
            ui.add(
                egui::DragValue::new(&mut frames)
                    .range(0..=100)
                    .suffix(" frames"),
            );
            ui.checkbox(&mut dynamic, "dynamic");
        }
        editor.misalign = on.then_some((frames, dynamic));
    });
}

/// The light items: a severity for `lights` and `daylight`, a frequency for `flicker`.
fn light_items(ui: &mut egui::Ui, light: &mut LightSpec) {
    severity_item(
        ui,
        "lights: lamps switched off and on",
        &mut light.lights,
        Switching::parse,
    );
    ui.horizontal(|ui| {
        let mut on = light.flicker.is_some();
        ui.checkbox(&mut on, "flicker (Hz)");
        let mut flicker = light.flicker.unwrap_or(Flicker {
            hz: 100.0,
            depth: None,
        });
        if on {
            ui.add(egui::DragValue::new(&mut flicker.hz).range(1.0..=1000.0));
        }
        light.flicker = on.then_some(flicker);
    });
    severity_item(
        ui,
        "daylight: clouds passing",
        &mut light.daylight,
        Daylight::parse,
    );
}

/// An item set by its severity (light, world): a checkbox and, when on, a slider. An explicit
/// form given on the command line stays until the slider moves.
fn severity_item<T: Copy + std::fmt::Display>(
    ui: &mut egui::Ui,
    label: &str,
    item: &mut Option<T>,
    parse: fn(&str) -> Result<T, String>,
) {
    ui.horizontal(|ui| {
        let mut on = item.is_some();
        ui.checkbox(&mut on, label);
        let written = item.map(|i| i.to_string());
        let before = (written.as_deref())
            .and_then(|t| t.rsplit(':').next()?.parse::<u8>().ok())
            .unwrap_or(3);
        let mut severity = before;
        if on {
            ui.add(egui::Slider::new(&mut severity, 1..=5));
        }
        if !on {
            *item = None;
        } else if item.is_none() || severity != before {
            *item = parse(&severity.to_string()).ok();
        }
    });
}

fn deviation(ui: &mut egui::Ui, label: &str, value: &mut Option<DeviationSetting>, start: f64) {
    ui.horizontal(|ui| {
        let mut on = value.is_some();
        ui.checkbox(&mut on, label);
        let mut setting = value.unwrap_or(DeviationSetting {
            sigma: start,
            smooth: false,
        });
        if on {
            ui.add(
                egui::DragValue::new(&mut setting.sigma)
                    .speed(start / 10.0)
                    .range(0.0..=90.0),
            );
            ui.checkbox(&mut setting.smooth, "smooth");
        }
        *value = on.then_some(setting);
    });
}
