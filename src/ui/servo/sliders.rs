//! Servo sliders: one row per servo of the project, sent live while dragged.
//! Keyboard: with a slider focused, ←/→ nudge by 1°, Shift+←/→ or
//! PageDown/PageUp by 10°.

use std::collections::{BTreeMap, HashMap};

use crate::device::servo::ServoStatus;
use crate::project::{Edit, Servo, ServoProject};
use crate::ui::action::Action;
use crate::ui::i18n::Strings;
use crate::ui::layout::{self, Layout, Pane};
use crate::ui::rows;
use crate::ui::servo::action::ServoAction;
use crate::ui::servo::captions::ServoWords;

/// What the panel draws.
#[derive(Debug)]
pub struct ServoView<'a> {
    /// The project, for its servos and limits.
    pub project: &'a ServoProject,
    /// The slider values.
    pub pose: &'a BTreeMap<u8, i16>,
    /// States read back from the board, when connected.
    pub readback: Option<&'a BTreeMap<u8, ServoStatus>>,
    /// Whether angles are being read back.
    pub polling: bool,
    /// Where a recording is, if one runs.
    pub recording: Option<crate::authoring::recording::Phase>,
    /// The servo selected (here or in the 3D view).
    pub selected: Option<u8>,
}

/// The servo panel's own state: which widget is whose slider.
#[derive(Debug, Default)]
pub struct ServoPanel {
    slider_ids: HashMap<egui::Id, u8>,
    /// The settings show the rig (else the limits).
    /// Which part of the servo settings is shown.
    part: super::rig::Part,
}

impl ServoPanel {
    /// Draws the panel: the sliders fill the height, the settings below them
    /// when open (the divider between them can be dragged).
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        view: &ServoView<'_>,
        layout: &mut Layout,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        ui.horizontal(|ui| {
            ui.heading(words.servos);
            if ui.button(words.servo().capture_pose).clicked() {
                actions.push(Action::family(ServoAction::CapturePose { from_board: false }));
            }
            match rows::record(ui, words, view.recording, words.servo().record_hint) {
                Some(true) => actions.push(Action::family(ServoAction::Record)),
                Some(false) => actions.push(Action::family(ServoAction::StopRecording)),
                None => {}
            }
            if view.readback.is_some() {
                if ui.button(words.servo().capture_from_board).clicked() {
                    actions.push(Action::family(ServoAction::CapturePose { from_board: true }));
                }
                let mut polling = view.polling;
                if ui.checkbox(&mut polling, words.servo().read_angles).changed() {
                    actions.push(Action::family(ServoAction::SetPolling(polling)));
                }
            }
        });
        if view.project.servos.is_empty() {
            ui.label(words.servo().no_servos);
        }
        let settings = (&mut layout.settings_share, &mut layout.settings_open);
        layout::over(ui, "servo-settings", settings, words.servo().servo_settings, |ui, pane| match pane {
            Pane::First => self.sliders(ui, view, words, actions),
            Pane::Second => {
                use super::rig::Part;
                ui.horizontal(|ui| {
                    ui.selectable_value(&mut self.part, Part::Limits, words.limits);
                    ui.selectable_value(&mut self.part, Part::Rig, words.rig);
                    ui.selectable_value(&mut self.part, Part::Ends, words.servo().ends_tab);
                    ui.selectable_value(&mut self.part, Part::Meshes, words.servo().meshes_tab);
                });
                let height = ui.available_height();
                match self.part {
                    Part::Limits => settings_ui(ui, view.project, words, actions),
                    Part::Rig => super::rig::table(ui, view.project, height, words, actions),
                    Part::Ends => super::rig::ends_table(ui, view.project, height, words, actions),
                    Part::Meshes => super::rig::meshes_table(ui, view.project, height, words, actions),
                }
            }
        });
    }

    fn sliders(&mut self, ui: &mut egui::Ui, view: &ServoView<'_>, words: &Strings, actions: &mut Vec<Action>) {
        let focused = ui.memory(|memory| memory.focused()).and_then(|id| self.slider_ids.get(&id).copied());
        let nudge = if focused.is_some() { rows::keyboard_nudge(ui) } else { 0 };
        self.slider_ids.clear();
        let newly_selected = rows::selection_changed(ui, "servo-selection", view.selected.as_ref());
        // The sliders take the width the panel has: no empty band beside the preview.
        ui.spacing_mut().slider_width = (ui.available_width() - 320.0).max(160.0);
        // Every slider the height holds; only those in view are laid out.
        let height = ui.available_height();
        rows::grid(ui, "servo-grid", view.project.servos.len(), height, |ui, index| {
            let servo = &view.project.servos[index];
            let current = view.pose.get(&servo.id).copied().unwrap_or(servo.home_deg);
            let selected = view.selected == Some(servo.id);
            let label = ui.selectable_label(selected, format!("{} #{}", servo.caption, servo.id));
            let mut value = i32::from(current);
            let slider = egui::Slider::new(&mut value, i32::from(servo.min_deg)..=i32::from(servo.max_deg))
                .step_by(1.0)
                .suffix("°");
            let response = ui.add(slider).labelled_by(label.id);
            if selected && newly_selected && !response.has_focus() {
                response.request_focus();
            }
            if !selected && (label.clicked() || response.gained_focus() || response.drag_started()) {
                actions.push(Action::family(ServoAction::SelectServo(Some(servo.id))));
            }
            if response.gained_focus() {
                // Tabbing onto a half-shown slider brings it into view.
                response.scroll_to_me(None);
            }
            self.slider_ids.insert(response.id, servo.id);
            if focused == Some(servo.id) && nudge != 0 {
                value += nudge;
            }
            if value != i32::from(current) {
                let degree = i16::try_from(value).unwrap_or(current);
                actions.push(Action::family(ServoAction::SetPose { servo_id: servo.id, degree: servo.clamp(degree) }));
            }
            if let Some(state) = view.readback.and_then(|servos| servos.get(&servo.id)) {
                let mut hold = state.is_hold;
                if ui.checkbox(&mut hold, words.servo().hold).changed() {
                    actions.push(Action::family(ServoAction::SetHold { servo_id: servo.id, hold }));
                }
                if view.polling {
                    ui.monospace(format!("{:>5}°", state.angle));
                }
            }
        });
    }
}

/// The servos' settings: caption, calibration offset, limits and home; add and
/// remove servos. A drag of one value is one undo step.
pub fn settings_ui(ui: &mut egui::Ui, project: &ServoProject, words: &Strings, actions: &mut Vec<Action>) {
    {
        let heading = [words.servo_id, words.caption, words.offset, words.min, words.max, words.home, ""];
        // The table takes the pane but for the "Add servo" row under it.
        let height = ui.available_height() - rows::widget_row_height(ui) - ui.spacing().item_spacing.y;
        rows::table(ui, "servo-settings", &heading, project.servos.len(), height, |row, index| {
            let servo = &project.servos[index];
            let set = |changed: Servo, field: &str| Action::Edit {
                edit: Edit::SetServo { index, servo: changed },
                coalesce: Some(format!("servo {} {field}", servo.id)),
            };
            let mut row_id = egui::Id::NULL;
            row.col(|ui| row_id = ui.label(format!("{}", servo.id)).id);
            row.col(|ui| {
                let mut caption = servo.caption.clone();
                if ui.add(egui::TextEdit::singleline(&mut caption).desired_width(200.0)).labelled_by(row_id).changed() {
                    actions.push(set(Servo { caption, ..servo.clone() }, "caption"));
                }
            });
            let fields: [(&str, i16); 4] = [
                ("offset", servo.calibration_offset_deg),
                ("min", servo.min_deg),
                ("max", servo.max_deg),
                ("home", servo.home_deg),
            ];
            for (field, value) in fields {
                row.col(|ui| {
                    let mut edited = value;
                    let drag = egui::DragValue::new(&mut edited).clamp_existing_to_range(false).suffix("°");
                    if ui.add(drag).labelled_by(row_id).changed() {
                        let mut changed = servo.clone();
                        match field {
                            "offset" => changed.calibration_offset_deg = edited,
                            "min" => changed.min_deg = edited,
                            "max" => changed.max_deg = edited,
                            _ => changed.home_deg = edited,
                        }
                        actions.push(set(changed, field));
                    }
                });
            }
            row.col(|ui| {
                if ui.button("×").on_hover_text(words.remove).clicked() {
                    actions.push(Action::Edit { edit: Edit::RemoveServo { index }, coalesce: None });
                }
            });
        });
        let free = (0..=254u8).find(|id| project.servo(*id).is_none());
        if ui.add_enabled(free.is_some(), egui::Button::new(words.servo().add_servo)).clicked()
            && let Some(id) = free
        {
            actions.push(Action::Edit {
                edit: Edit::AddServo(Servo::new(id, format!("{} {id}", words.servo().servo_word))),
                coalesce: None,
            });
        }
    }
}
