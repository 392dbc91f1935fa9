//! PLEN2 play lists, and the robot panel: a map of the 90 slots (the
//! project's motion and the robot's, differences marked), read the robot,
//! upload with backup and verification, read into the project, export to a file.

use crate::device::plen2::Plen2Phase;
use crate::project::Edit;
use crate::project::plen2::{Motion, PlayEntry, PlayList, Plen2Project, SLOTS};
use crate::ui::action::{Action, Plen2Intent};
use crate::ui::i18n::Strings;
use crate::ui::plen2_job::Plen2Job;

/// Draws the play lists.
pub fn play_lists(
    ui: &mut egui::Ui,
    project: &Plen2Project,
    connected: bool,
    words: &Strings,
    actions: &mut Vec<Action>,
) {
    let edit = |change: &dyn Fn(&mut Plen2Project)| {
        let mut changed = project.clone();
        change(&mut changed);
        Action::Edit { edit: Edit::SetPlen2(Box::new(changed)), coalesce: Some("plen2 play lists".into()) }
    };
    ui.horizontal(|ui| {
        ui.heading(words.play_lists);
        if ui.button(words.add_play_list).clicked() {
            let name = format!("{} {}", words.play_lists, project.play_lists.len() + 1);
            actions.push(edit(&|p| p.play_lists.push(PlayList { name: name.clone(), entries: Vec::new() })));
        }
    });
    for (index, list) in project.play_lists.iter().enumerate() {
        ui.separator();
        ui.horizontal(|ui| {
            let mut name = list.name.clone();
            if ui.text_edit_singleline(&mut name).changed() {
                actions.push(edit(&|p| p.play_lists[index].name = name.clone()));
            }
            if ui
                .add_enabled(connected && !list.entries.is_empty(), egui::Button::new(words.play_on_robot))
                .on_hover_text("#RI, #PU…, #PO")
                .clicked()
            {
                actions.push(Action::PlayList(index));
            }
            if ui.button(words.add_entry).clicked() {
                let slot = project.motions.first().map_or(0, |m| m.slot);
                actions.push(edit(&|p| p.play_lists[index].entries.push(PlayEntry { slot, plays: 1 })));
            }
            if ui.button(words.remove).clicked() {
                actions.push(edit(&|p| {
                    p.play_lists.remove(index);
                }));
            }
        });
        for (position, entry) in list.entries.iter().enumerate() {
            ui.horizontal(|ui| {
                let mut changed = *entry;
                let name = project.motions.iter().find(|m| m.slot == entry.slot).map_or("—", |m| m.name.as_str());
                egui::ComboBox::from_id_salt(("plen2-entry", index, position))
                    .selected_text(format!("{} {name}", entry.slot))
                    .show_ui(ui, |ui| {
                        for motion in &project.motions {
                            ui.selectable_value(
                                &mut changed.slot,
                                motion.slot,
                                format!("{} {}", motion.slot, motion.name),
                            );
                        }
                    });
                ui.label(words.plays);
                ui.add(egui::DragValue::new(&mut changed.plays));
                if changed != *entry {
                    actions.push(edit(&|p| p.play_lists[index].entries[position] = changed));
                }
                if ui.small_button("×").clicked() {
                    actions.push(edit(&|p| {
                        p.play_lists[index].entries.remove(position);
                    }));
                }
            });
        }
    }
}

/// What the robot panel draws.
#[derive(Debug)]
pub struct RobotView<'a> {
    /// The project's PLEN2 section.
    pub project: &'a Plen2Project,
    /// What the robot held when last read.
    pub robot: Option<&'a Plen2Project>,
    /// Whether a robot is connected.
    pub connected: bool,
    /// The running operation.
    pub job: Option<&'a Plen2Job>,
    /// The last outcome, in words.
    pub result: Option<&'a str>,
}

fn cell(ui: &mut egui::Ui, slot: u8, ours: Option<&Motion>, theirs: Option<&Motion>, read: bool) {
    let visuals = ui.visuals().clone();
    let (fill, text) = match (ours, theirs) {
        (Some(a), Some(b)) if a == b => (egui::Color32::from_rgb(40, 110, 60), a.name.clone()),
        (Some(a), Some(_)) => (egui::Color32::from_rgb(150, 110, 20), a.name.clone()),
        (Some(a), None) if read => (egui::Color32::from_rgb(40, 80, 140), a.name.clone()),
        (Some(a), None) => (visuals.widgets.inactive.bg_fill, a.name.clone()),
        (None, Some(b)) => (visuals.widgets.noninteractive.bg_fill, format!("({})", b.name)),
        (None, None) => (visuals.extreme_bg_color, String::new()),
    };
    let (rect, response) = ui.allocate_exact_size(egui::vec2(104.0, 30.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect.shrink(1.0), 3.0, fill);
    painter.text(
        rect.left_top() + egui::vec2(4.0, 2.0),
        egui::Align2::LEFT_TOP,
        slot.to_string(),
        egui::FontId::monospace(9.0),
        visuals.weak_text_color(),
    );
    painter.text(
        rect.left_bottom() + egui::vec2(4.0, -3.0),
        egui::Align2::LEFT_BOTTOM,
        &text,
        egui::FontId::proportional(11.0),
        visuals.text_color(),
    );
    if !text.is_empty() {
        response.on_hover_text(text);
    }
}

fn phase_word(phase: Plen2Phase, words: &Strings) -> &'static str {
    match phase {
        Plen2Phase::Read => words.phases[0],
        Plen2Phase::Write => words.phases[1],
        Plen2Phase::Verify => words.phases[2],
    }
}

/// Draws the robot panel.
pub fn robot_panel(ui: &mut egui::Ui, view: &RobotView<'_>, words: &Strings, actions: &mut Vec<Action>) {
    ui.horizontal(|ui| {
        ui.heading(words.board);
        let idle = view.job.is_none();
        ui.add_enabled_ui(view.connected && idle, |ui| {
            if ui.button(words.read_robot).clicked() {
                actions.push(Action::Plen2Board(Plen2Intent::Read));
            }
            if ui.button(words.upload_motions).on_hover_text(words.upload_hint).clicked() {
                actions.push(Action::Plen2Board(Plen2Intent::Upload));
            }
            if ui.add_enabled(view.robot.is_some(), egui::Button::new(words.confirm_read)).clicked() {
                actions.push(Action::Plen2Board(Plen2Intent::ReadIntoProject));
            }
            if ui.add_enabled(view.robot.is_some(), egui::Button::new(words.export_board)).clicked()
                && let Some(path) = rfd::FileDialog::new()
                    .add_filter("Servo Studio project", &["json"])
                    .set_file_name("plen2.json")
                    .save_file()
            {
                actions.push(Action::Plen2Board(Plen2Intent::ExportToFile(path)));
            }
        });
    });
    if !view.connected {
        ui.label(words.connect_to_transfer);
    }
    if let Some(job) = view.job {
        if let Some(progress) = &job.progress {
            let fraction = if progress.total == 0 { 0.0 } else { progress.done as f32 / progress.total as f32 };
            ui.add(egui::ProgressBar::new(fraction).show_percentage().text(format!(
                "{} {}/{} {}",
                phase_word(progress.phase, words),
                progress.done,
                progress.total,
                progress.item
            )));
        }
        if ui.button(words.cancel).clicked() {
            actions.push(Action::BoardCancel);
        }
    }
    if let Some(result) = view.result {
        ui.label(result);
    }
    ui.label(words.slot_map);
    egui::ScrollArea::vertical().id_salt("plen2-slot-map").show(ui, |ui| {
        egui::Grid::new("plen2-slots").spacing([2.0, 2.0]).show(ui, |ui| {
            for slot in 0..SLOTS {
                let ours = view.project.motions.iter().find(|m| m.slot == slot);
                let theirs = view.robot.and_then(|robot| robot.motions.iter().find(|m| m.slot == slot));
                cell(ui, slot, ours, theirs, view.robot.is_some());
                if slot % 10 == 9 {
                    ui.end_row();
                }
            }
        });
    });
}
