//! PLEN2 joint sliders: the 18 joints by name, each within the limits the robot
//! holds (the project's joint settings, else the factory table), sent live
//! with `$AN` (coalesced and paced); Home; capture the pose into a frame of the
//! selected motion. Keyboard: with a slider focused, ←/→ nudge by 1°,
//! Shift+←/→ or PageDown/PageUp by 10°. Below, the joint settings editor
//! (min / max / home).

use crate::project::Edit;
use crate::project::plen2::{FACTORY_LIMIT_TENTHS_DEG, Joint, JointSetting, Plen2Project};
use crate::ui::action::Action;
use crate::ui::i18n::Strings;
use crate::ui::layout::{self, Layout, Pane};
use crate::ui::plen2::action::{Plen2Action, Plen2Intent};
use crate::ui::plen2::captions::Plen2Words;
use crate::ui::rows;

/// The limits and home a joint has: the project's settings, else the factory's.
pub fn limits(project: &Plen2Project, joint: Joint) -> JointSetting {
    project.joints.iter().find(|s| s.joint == joint).copied().unwrap_or(JointSetting {
        joint,
        min_tenths_deg: -FACTORY_LIMIT_TENTHS_DEG,
        max_tenths_deg: FACTORY_LIMIT_TENTHS_DEG,
        home_tenths_deg: joint.factory_home_tenths_deg(),
    })
}

/// What the panel draws.
#[derive(Debug)]
pub struct JointsView<'a> {
    /// The PLEN2 section.
    pub project: &'a Plen2Project,
    /// Every joint's angle, tenths of a degree, in device-map order.
    pub pose: &'a [i16; 18],
    /// Whether a robot is connected.
    pub connected: bool,
    /// The slot frames are captured into.
    pub capture_slot: Option<u8>,
    /// Where a recording is, if one runs.
    pub recording: Option<crate::authoring::recording::Phase>,
    /// The joint selected (here or in the 3D view).
    pub selected: Option<Joint>,
}

/// Draws the panel: the 18 joints fill the height, the joint settings below
/// them when open.
pub fn ui(ui: &mut egui::Ui, view: &JointsView<'_>, layout: &mut Layout, words: &Strings, actions: &mut Vec<Action>) {
    ui.horizontal(|ui| {
        ui.heading(words.joints);
        if ui.add_enabled(view.connected, egui::Button::new(words.home)).clicked() {
            actions.push(Action::family(Plen2Action::Home));
        }
        if let Some(slot) = view.capture_slot
            && ui.button(format!("{} ({} {slot})", words.plen2().capture_frame, words.slot)).clicked()
        {
            actions.push(Action::family(Plen2Action::CaptureFrame { slot }));
        }
        if view.capture_slot.is_some() || view.recording.is_some() {
            match rows::record(ui, words, view.recording, words.plen2().record_hint) {
                Some(true) => {
                    if let Some(slot) = view.capture_slot {
                        actions.push(Action::family(Plen2Action::Record { slot }));
                    }
                }
                Some(false) => actions.push(Action::family(Plen2Action::StopRecording)),
                None => {}
            }
        }
    });
    let settings = (&mut layout.settings_share, &mut layout.settings_open);
    layout::over(ui, "plen2-joint-settings", settings, words.plen2().joint_settings, |ui, pane| match pane {
        Pane::First => sliders(ui, view, words.home, actions),
        Pane::Second => {
            egui::ScrollArea::vertical().id_salt("plen2-settings-scroll").show(ui, |ui| {
                settings_editor(ui, view, words, actions);
            });
        }
    });
}

/// The 18 joints' sliders, in the height left (only the rows in view laid out).
fn sliders(ui: &mut egui::Ui, view: &JointsView<'_>, home: &str, actions: &mut Vec<Action>) {
    // Which slider is whose joint, remembered from the last frame (egui gives
    // widgets their ids as they are drawn).
    let ids_key = ui.scope_id().with("plen2-joint-slider-ids");
    let previous: Vec<(egui::Id, Joint)> = ui.data(|data| data.get_temp(ids_key)).unwrap_or_default();
    let focused = ui
        .memory(|memory| memory.focused())
        .and_then(|id| previous.iter().find(|(i, _)| *i == id).map(|&(_, joint)| joint));
    // Tenths of a degree: a step is 1°.
    let nudge = if focused.is_some() { i16::try_from(rows::keyboard_nudge(ui) * 10).unwrap_or(0) } else { 0 };
    let newly_selected = rows::selection_changed(ui, "plen2-joint-selection", view.selected.as_ref());
    let mut ids = Vec::with_capacity(Joint::ALL.len());
    // The sliders take the width the panel has: no empty band beside the preview.
    ui.spacing_mut().slider_width = (ui.available_width() - 340.0).max(160.0);
    let height = ui.available_height();
    rows::grid(ui, "plen2-joint-sliders", Joint::ALL.len(), height, |ui, index| {
        let joint = Joint::ALL[index];
        let setting = limits(view.project, joint);
        let selected = view.selected == Some(joint);
        let label = ui.selectable_label(selected, format!("{} #{}", joint.name(), joint.device_id()));
        let mut value = view.pose[joint.index()];
        let low = setting.min_tenths_deg.min(setting.max_tenths_deg);
        let high = setting.max_tenths_deg.max(setting.min_tenths_deg);
        let slider =
            egui::Slider::new(&mut value, low..=high).custom_formatter(|v, _| format!("{:.1}°", v / 10.0)).step_by(1.0);
        let response = ui.add(slider).labelled_by(label.id);
        ids.push((response.id, joint));
        if selected && newly_selected && !response.has_focus() {
            response.request_focus();
        }
        if !selected && (label.clicked() || response.gained_focus() || response.drag_started()) {
            actions.push(Action::family(Plen2Action::SelectJoint(Some(joint))));
        }
        if focused == Some(joint) && nudge != 0 {
            value = value.saturating_add(nudge).clamp(low, high);
        }
        if response.changed() || (focused == Some(joint) && nudge != 0) {
            actions.push(Action::family(Plen2Action::SetJoint { joint, tenths: value }));
        }
        ui.weak(format!("{home} {:.1}°", f64::from(setting.home_tenths_deg) / 10.0));
    });
    ui.data_mut(|data| data.insert_temp(ids_key, ids));
}

fn settings_editor(ui: &mut egui::Ui, view: &JointsView<'_>, words: &Strings, actions: &mut Vec<Action>) {
    let mut project = view.project.clone();
    let mut changed = false;
    egui::Grid::new("plen2-settings").striped(true).show(ui, |ui| {
        ui.label("");
        ui.label(words.min);
        ui.label(words.max);
        ui.label(words.home);
        ui.end_row();
        for joint in Joint::ALL {
            let mut setting = limits(&project, joint);
            ui.label(joint.name());
            let range = -FACTORY_LIMIT_TENTHS_DEG..=FACTORY_LIMIT_TENTHS_DEG;
            changed |= ui
                .add(
                    egui::DragValue::new(&mut setting.min_tenths_deg)
                        .clamp_existing_to_range(false)
                        .range(range.clone()),
                )
                .changed();
            changed |= ui
                .add(
                    egui::DragValue::new(&mut setting.max_tenths_deg)
                        .clamp_existing_to_range(false)
                        .range(range.clone()),
                )
                .changed();
            changed |= ui
                .add(egui::DragValue::new(&mut setting.home_tenths_deg).clamp_existing_to_range(false).range(range))
                .changed();
            ui.end_row();
            match project.joints.iter_mut().find(|s| s.joint == joint) {
                Some(slot) => *slot = setting,
                None if setting != limits(view.project, joint) => project.joints.push(setting),
                None => {}
            }
        }
    });
    if changed {
        actions.push(Action::Edit {
            edit: Edit::SetPlen2(Box::new(project)),
            coalesce: Some("plen2 joint settings".into()),
        });
    }
    ui.horizontal(|ui| {
        if ui
            .add_enabled(
                view.connected && !view.project.joints.is_empty(),
                egui::Button::new(words.plen2().write_joints),
            )
            .clicked()
        {
            actions.push(Action::family(Plen2Action::Robot(Plen2Intent::WriteJoints)));
        }
        if ui.add_enabled(view.connected, egui::Button::new(words.plen2().factory_reset)).clicked() {
            actions.push(Action::family(Plen2Action::Robot(Plen2Intent::FactoryReset)));
        }
    });
}

#[cfg(test)]
mod tests {
    use egui::accesskit::Role;
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable;

    use super::*;
    use crate::ui::i18n::Language;

    type Panel = (Layout, Vec<Action>);

    fn joints(project: Plen2Project, connected: bool) -> Harness<'static, Panel> {
        let pose = super::super::homes(&project);
        Harness::builder()
            .with_size(egui::vec2(900.0, 700.0))
            .with_context_setup(crate::ui::fonts::install)
            .build_ui_state(
                move |panel, (layout, actions): &mut Panel| {
                    let view = JointsView {
                        project: &project,
                        pose: &pose,
                        connected,
                        capture_slot: Some(3),
                        recording: None,
                        selected: None,
                    };
                    ui(panel, &view, layout, Language::English.strings(), actions);
                },
                (Layout::default(), Vec::new()),
            )
    }

    fn set(actions: &[Action]) -> Vec<(Joint, i16)> {
        actions
            .iter()
            .filter_map(|action| match action.family_action() {
                Some(Plen2Action::SetJoint { joint, tenths }) => Some((*joint, *tenths)),
                _ => None,
            })
            .collect()
    }

    /// ←/→ on a focused joint move it 1° (10 tenths), Shift 10°, never past
    /// the limit the robot holds.
    #[test]
    fn keys_nudge_the_focused_joint_within_its_limits() {
        let mut project = Plen2Project::default();
        let joint = Joint::ALL[0];
        let home = joint.factory_home_tenths_deg();
        project.joints.push(JointSetting {
            joint,
            min_tenths_deg: home - 50,
            max_tenths_deg: home + 15,
            home_tenths_deg: home,
        });
        let mut harness = joints(project, true);
        harness.run();
        harness.get_all_by_role(Role::Slider).next().unwrap().focus();
        harness.run();
        harness.key_press(egui::Key::ArrowRight);
        harness.run();
        assert_eq!(set(&harness.state().1), [(joint, home + 10)]);
        harness.key_press_modifiers(egui::Modifiers::SHIFT, egui::Key::ArrowLeft);
        harness.run();
        assert_eq!(set(&harness.state().1)[1], (joint, home - 50), "10° down from home stops at the 5° limit");
    }

    #[test]
    fn home_needs_a_robot_and_capture_goes_to_the_selected_motion() {
        let mut harness = joints(Plen2Project::default(), false);
        harness.run();
        harness.get_by_label("Home").click();
        harness.get_by_label_contains("Capture into frame").click();
        harness.run();
        assert_eq!(harness.state().1, [Action::family(Plen2Action::CaptureFrame { slot: 3 })]);
    }
}
