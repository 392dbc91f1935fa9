//! The PLEN2 robot panel: a map of the 90 slots (the
//! project's motion and the robot's, differences marked), read the robot,
//! upload with backup and verification, read into the project, export to a file.

use super::Plen2Result;
use crate::device::Phase;
use crate::project::plen2::{Motion, Plen2Project, SLOTS};
use crate::ui::action::{Action, Export, FileRequest, PROJECT_FILE};
use crate::ui::i18n::Worded;
use crate::ui::i18n::{Language, Strings};
use crate::ui::plen2::action::{Plen2Action, Plen2Intent};
use crate::ui::plen2::captions::Plen2Words;
use crate::ui::rows;

/// What the robot panel draws.
#[derive(Debug)]
pub struct RobotView<'a> {
    /// The 90 slots, the project's motions compared with the robot's ([`slot_map`]).
    pub slots: &'a [SlotCell],
    /// Whether the robot has been read.
    pub robot_read: bool,
    /// Whether a robot is connected.
    pub connected: bool,
    /// The running operation.
    pub operation: Option<&'a super::Plen2Operation>,
    /// The last outcome.
    pub result: Option<&'a Plen2Result>,
}

/// How a slot of the map compares the project with the robot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlotState {
    /// Neither holds a motion there.
    Empty,
    /// The project's motion; the robot not read.
    Ours,
    /// The project's motion; the robot, read, holds none.
    OnlyOurs,
    /// Only the robot holds one.
    OnlyTheirs,
    /// Both hold the same motion.
    Same,
    /// Both hold one, and they differ.
    Differ,
}

/// One slot of the map: how it compares, and the name shown.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SlotCell {
    /// How the project's slot compares with the robot's.
    pub state: SlotState,
    /// The motion's name (the robot's in brackets when only it holds one).
    pub name: String,
}

/// The 90 slots compared (computed once per document revision and robot read).
pub fn slot_map(project: &Plen2Project, robot: Option<&Plen2Project>) -> Vec<SlotCell> {
    let mut ours: Vec<Option<&Motion>> = vec![None; usize::from(SLOTS)];
    let mut theirs: Vec<Option<&Motion>> = vec![None; usize::from(SLOTS)];
    for motion in &project.motions {
        if let Some(cell) = ours.get_mut(usize::from(motion.slot)) {
            cell.get_or_insert(motion);
        }
    }
    for motion in robot.map_or(&[][..], |robot| robot.motions.as_slice()) {
        if let Some(cell) = theirs.get_mut(usize::from(motion.slot)) {
            cell.get_or_insert(motion);
        }
    }
    ours.into_iter()
        .zip(theirs)
        .map(|(ours, theirs)| match (ours, theirs) {
            (Some(a), Some(b)) if a == b => SlotCell { state: SlotState::Same, name: a.name.clone() },
            (Some(a), Some(_)) => SlotCell { state: SlotState::Differ, name: a.name.clone() },
            (Some(a), None) if robot.is_some() => SlotCell { state: SlotState::OnlyOurs, name: a.name.clone() },
            (Some(a), None) => SlotCell { state: SlotState::Ours, name: a.name.clone() },
            (None, Some(b)) => SlotCell { state: SlotState::OnlyTheirs, name: format!("({})", b.name) },
            (None, None) => SlotCell { state: SlotState::Empty, name: String::new() },
        })
        .collect()
}

fn cell(ui: &mut egui::Ui, slot: usize, cell: &SlotCell) {
    let visuals = ui.visuals();
    let fill = match cell.state {
        SlotState::Same => egui::Color32::from_rgb(40, 110, 60),
        SlotState::Differ => egui::Color32::from_rgb(150, 110, 20),
        SlotState::OnlyOurs => egui::Color32::from_rgb(40, 80, 140),
        SlotState::Ours => visuals.widgets.inactive.bg_fill,
        SlotState::OnlyTheirs => visuals.widgets.noninteractive.bg_fill,
        SlotState::Empty => visuals.extreme_bg_color,
    };
    let (weak, strong) = (visuals.weak_text_color(), visuals.text_color());
    let (rect, response) = ui.allocate_exact_size(egui::vec2(112.0, 40.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect.shrink(1.0), 3.0, fill);
    painter.text(
        rect.left_top() + egui::vec2(4.0, 2.0),
        egui::Align2::LEFT_TOP,
        slot.to_string(),
        egui::TextStyle::Monospace.resolve(ui.style()),
        weak,
    );
    painter.text(
        rect.left_bottom() + egui::vec2(4.0, -3.0),
        egui::Align2::LEFT_BOTTOM,
        &cell.name,
        egui::TextStyle::Body.resolve(ui.style()),
        strong,
    );
    let label = format!("{slot} {}", cell.name);
    response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Label, true, &label));
    if !cell.name.is_empty() {
        response.on_hover_text(&cell.name);
    }
}

fn phase_word(phase: Phase, words: &Strings) -> &'static str {
    match phase {
        Phase::Read => words.phases[0],
        Phase::Write => words.phases[1],
        Phase::Verify => words.phases[2],
    }
}

/// Draws the robot panel.
pub fn robot_panel(ui: &mut egui::Ui, view: &RobotView<'_>, language: Language, actions: &mut Vec<Action>) {
    let words = language.strings();
    ui.horizontal(|ui| {
        ui.heading(words.board);
        let idle = view.operation.is_none();
        ui.add_enabled_ui(view.connected && idle, |ui| {
            if ui.button(words.plen2().read_robot).clicked() {
                actions.push(Action::family(Plen2Action::Robot(Plen2Intent::Read)));
            }
            if ui.button(words.plen2().upload_motions).on_hover_text(words.upload_hint).clicked() {
                actions.push(Action::family(Plen2Action::Robot(Plen2Intent::Upload)));
            }
            if ui.add_enabled(view.robot_read, egui::Button::new(words.confirm_read)).clicked() {
                actions.push(Action::family(Plen2Action::Robot(Plen2Intent::ReadIntoProject)));
            }
            // The shell asks where, off the frame.
            if ui.add_enabled(view.robot_read, egui::Button::new(words.export_board)).clicked() {
                actions.push(Action::AskFile(FileRequest::Export(Export::json("plen2.json", PROJECT_FILE, |path| {
                    Action::family(Plen2Action::Robot(Plen2Intent::ExportToFile(path)))
                }))));
            }
        });
    });
    if !view.connected {
        ui.label(words.connect_to_transfer);
    }
    if let Some(operation) = view.operation {
        if let Some(progress) = &operation.progress {
            let item = progress.item.worded(language);
            ui.add(egui::ProgressBar::new(operation.fraction()).show_percentage().text(format!(
                "{} {}/{} {item}",
                phase_word(progress.phase, words),
                progress.done,
                progress.total,
            )));
        }
        if ui.button(words.cancel).clicked() {
            actions.push(Action::CancelOperation);
        }
    }
    if let Some(result) = view.result {
        let (text, is_error) = result.words(language);
        if is_error {
            ui.colored_label(ui.visuals().error_fg_color, text);
        } else {
            ui.label(text);
        }
    }
    ui.label(words.plen2().slot_map);
    // Ten slots a row; only the rows in view are laid out.
    let per_row = 10;
    let rows_count = view.slots.len().div_ceil(per_row);
    ui.spacing_mut().item_spacing = egui::vec2(2.0, 2.0);
    // Each row is laid out left to right already.
    rows::list(ui, "plen2-slot-map", 40.0, rows_count, ui.available_height(), |ui, row| {
        let first = row * per_row;
        for (slot, slot_cell) in view.slots.iter().enumerate().skip(first).take(per_row) {
            cell(ui, slot, slot_cell);
        }
    });
}
