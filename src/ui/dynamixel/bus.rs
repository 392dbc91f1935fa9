//! The Bus panel: the scan, and a row per servo — its slider (degrees,
//! clamped to its own limits; arrow keys nudge the focused one), torque, LED,
//! and what it says live: position, load, voltage, temperature, hardware
//! errors, or that it is silent. Capture (C) and Record pose by hand.

use egui::{Color32, RichText};

use super::{DynamixelAction, DynamixelUi, degrees, units};
use crate::device::dynamixel::HARDWARE_ERRORS;
use crate::project::dynamixel::{DynamixelSection, Profile, ServoSetup};
use crate::ui::action::Action;
use crate::ui::i18n::Language;
use crate::ui::shell::ShellView;

/// Draws the Bus panel.
pub fn ui(family: &mut DynamixelUi, ui: &mut egui::Ui, view: &ShellView<'_>, actions: &mut Vec<Action>) {
    let language = view.language;
    let word = |key: &str| language.word(key);
    let connected = view.link.is_some();
    toolbar(family, ui, view, actions);
    if let Some((done, of)) = family.bus.scanning {
        #[allow(clippy::cast_precision_loss)]
        let part = done as f32 / of.max(1) as f32;
        ui.add(egui::ProgressBar::new(part).text(crate::say!(language, "dynamixel.scanning", done, of)));
    }
    if !connected {
        ui.label(word("dynamixel.connect_hint"));
        return;
    }
    if family.bus.servos.is_empty() && family.bus.scanning.is_none() {
        ui.label(word("dynamixel.none_found"));
        return;
    }
    let section = DynamixelSection::of(view.project);
    egui::ScrollArea::both().auto_shrink([false, false]).show(ui, |ui| {
        // Sliders long enough to place a servo to a tenth of a degree by hand.
        ui.spacing_mut().slider_width = (ui.available_width() - 760.0).clamp(160.0, 420.0);
        egui::Grid::new("dynamixel_bus").striped(true).num_columns(13).show(ui, |ui| {
            for heading in [
                "id",
                "model",
                "caption",
                "position",
                "speed",
                "torque",
                "led",
                "load",
                "voltage",
                "temperature",
                "errors",
            ] {
                ui.strong(word(&format!("dynamixel.col_{heading}")));
            }
            ui.end_row();
            for servo in family.bus.servos.values() {
                let id = servo.found.id;
                ui.label(id.to_string());
                let protocol =
                    if servo.found.protocol == crate::device::dynamixel::Protocol::Two { "2.0" } else { "1.0" };
                ui.label(format!("{} v{} · {protocol}", servo.found.model_name(), servo.found.firmware))
                    .on_hover_text(format!("model number {}", servo.found.model_number));
                let kept = section.servo(id).map_or("", |setup| setup.name.as_str());
                let mut renamed = family.with_bus(view.project);
                let draft = family.captions.entry(id).or_insert_with(|| kept.to_string());
                let edited = ui.add_sized(
                    [150.0, ui.spacing().interact_size.y],
                    egui::TextEdit::singleline(draft).hint_text(word("dynamixel.caption_hint")),
                );
                if edited.lost_focus() && draft != kept {
                    if let Some(setup) = renamed.servos.iter_mut().find(|setup| setup.id == id) {
                        setup.name.clone_from(draft);
                    }
                    actions.push(Action::family(DynamixelAction::Edit(Box::new(renamed))));
                } else if !edited.has_focus() && draft != kept {
                    // Undone or replaced: the kept caption shows again.
                    *draft = kept.to_string();
                }
                let profile = section.servo(id).map_or(Profile::LIVE, ServoSetup::live_profile);
                row(ui, servo, profile, language, actions);
                ui.end_row();
            }
        });
    });
}

/// The bus's buttons: scan, torque on, relax; capture (C), record and its tolerance.
fn toolbar(family: &mut DynamixelUi, ui: &mut egui::Ui, view: &ShellView<'_>, actions: &mut Vec<Action>) {
    let word = |key: &str| view.language.word(key);
    let connected = view.link.is_some();
    ui.horizontal_wrapped(|ui| {
        if ui.add_enabled(connected, egui::Button::new(word("dynamixel.scan"))).clicked() {
            actions.push(Action::family(DynamixelAction::Scan));
        }
        if ui.add_enabled(connected, egui::Button::new(word("dynamixel.torque_all_on"))).clicked() {
            actions.push(Action::family(DynamixelAction::Torque { id: None, on: true }));
        }
        if ui.add_enabled(connected, egui::Button::new(word("dynamixel.relax"))).clicked() {
            actions.push(Action::family(DynamixelAction::Relax));
        }
        ui.separator();
        let capture = ui.add_enabled(connected, egui::Button::new(word("dynamixel.capture")));
        let typed_c =
            connected && ui.input(|input| input.key_pressed(egui::Key::C)) && !ui.ctx().egui_wants_keyboard_input();
        if capture.clicked() || typed_c {
            actions.push(Action::family(DynamixelAction::Capture));
        }
        let recording = family.recording.is_some();
        let record_label = if recording { word("dynamixel.record_stop") } else { word("dynamixel.record") };
        // A recording whose cable was pulled can still be stopped and kept.
        if ui.add_enabled(connected || recording, egui::Button::new(record_label).selected(recording)).clicked() {
            actions.push(Action::family(DynamixelAction::Record(!recording)));
        }
        ui.label(word("dynamixel.tolerance"));
        if family.tolerance_deg <= 0.0 {
            family.tolerance_deg = super::record::TOLERANCE_DEG;
        }
        ui.add(egui::DragValue::new(&mut family.tolerance_deg).range(0.1..=20.0).speed(0.1).suffix("°"));
    });
}

/// One servo's row.
fn row(ui: &mut egui::Ui, servo: &super::BusServo, profile: Profile, language: Language, actions: &mut Vec<Action>) {
    let id = servo.found.id;
    let model = servo.found.model_number;
    let (lowest, highest) = servo.range();
    let mut deg = servo.shown().map_or(0.0, |position| degrees(model, position));
    let slider =
        egui::Slider::new(&mut deg, degrees(model, lowest)..=degrees(model, highest)).fixed_decimals(1).suffix("°");
    let moved = ui.add_enabled(servo.reading.is_some(), slider);
    // Only the user's hand moves a servo: a slider that merely shows where the
    // servo is (clamped into its range as it draws) sends nothing.
    if moved.changed() && (moved.dragged() || moved.has_focus()) {
        actions.push(Action::family(DynamixelAction::Goal { id, position: servo.clamp(units(model, deg)) }));
    }
    // Its own profile: how fast a live move goes (0: as fast as it can), said in degrees a second.
    let mut velocity = profile.velocity;
    let per_unit =
        servo.found.model().map_or(0.0, |model| model.layout.at.speed_unit * 360.0 / model.layout.units_per_turn);
    #[allow(clippy::cast_precision_loss)]
    let shown = if velocity == 0 { "max".to_string() } else { format!("≈{:.0}°/s", f64::from(velocity) * per_unit) };
    let speed = ui.add(egui::DragValue::new(&mut velocity).range(0..=1023).speed(2).suffix(format!(" ({shown})")));
    if speed.changed() {
        let profile = Profile { velocity, ..profile };
        actions.push(Action::family(DynamixelAction::Profile { id, profile }));
    }
    let mut torque = servo.torque;
    if ui.checkbox(&mut torque, "").changed() {
        actions.push(Action::family(DynamixelAction::Torque { id: Some(id), on: torque }));
    }
    let mut led = servo.led;
    if ui.checkbox(&mut led, "").changed() {
        actions.push(Action::family(DynamixelAction::Led { id, on: led }));
    }
    match servo.reading {
        Some(reading) => {
            ui.label(format!("{:+.1} %", reading.load_percent));
            ui.label(format!("{:.1} V", reading.volts));
            let hot = servo.limits.is_some_and(|limits| reading.temperature_c >= limits.temperature_limit_c);
            let temperature = RichText::new(format!("{} °C", reading.temperature_c));
            ui.label(if hot { temperature.color(Color32::RED) } else { temperature });
            let errors: Vec<&str> = HARDWARE_ERRORS
                .iter()
                .filter(|(bit, _)| reading.hardware_error & bit != 0)
                .map(|(_, name)| language.word(&format!("dynamixel.error_{}", name.replace(' ', "_"))))
                .collect();
            if servo.silent {
                ui.label(RichText::new(language.word("dynamixel.silent_short")).color(Color32::RED));
            } else if errors.is_empty() {
                ui.label("—");
            } else {
                ui.label(RichText::new(errors.join(", ")).color(Color32::RED));
            }
        }
        None => {
            for _ in 0..4 {
                ui.label("…");
            }
        }
    }
}
