//! The board panel: memory meter, upload to board, read board into project,
//! export board to file — each starts by reading the board and showing what
//! differs, and overwrites nothing until the user confirms.

use super::operations::{BoardResult, PendingConfirm, ServoKind};
use crate::device::servo::Item;
use crate::ui::action::{Action, Export, FileRequest, PROJECT_FILE};
use crate::ui::i18n::Language;
use crate::ui::i18n::Worded;
use crate::ui::rows;
use crate::ui::servo::action::{BoardIntent, ServoAction};
use crate::ui::servo::captions::ServoWords;

/// The differences of a comparison in `language`.
pub fn difference_lines(pending: &PendingConfirm, language: Language) -> Vec<String> {
    match &pending.differences {
        Ok(differences) => differences.iter().map(|d| d.worded(language)).collect(),
        Err(error) => vec![crate::device::servo::OpError::Image(error.clone()).worded(language)],
    }
}

/// What the panel draws.
#[derive(Debug)]
pub struct BoardView<'a> {
    /// Whether a board is connected.
    pub connected: bool,
    /// Bytes the project needs on the board, or why it cannot be stored.
    pub project_bytes: Result<usize, String>,
    /// The board's total memory, if known.
    pub board_total_bytes: Option<i64>,
    /// The running operation.
    pub operation: Option<&'a super::operations::ServoOperation>,
    /// A comparison waiting for confirmation.
    pub pending: Option<&'a PendingConfirm>,
    /// The last outcome.
    pub result: Option<&'a BoardResult>,
}

/// Draws the board panel.
pub fn ui(ui: &mut egui::Ui, view: &BoardView<'_>, language: Language, actions: &mut Vec<Action>) {
    let words = language.strings();
    ui.heading(words.board);
    match (&view.project_bytes, view.board_total_bytes) {
        (Ok(bytes), Some(total)) if total > 0 => {
            let fraction = *bytes as f32 / total as f32;
            let bar = egui::ProgressBar::new(fraction.min(1.0)).text(format!(
                "{} {bytes} {} {total}",
                words.servo().project_needs,
                words.servo().of_capacity
            ));
            ui.add(bar.fill(if fraction > 1.0 { ui.visuals().error_fg_color } else { ui.visuals().selection.bg_fill }));
        }
        (Ok(bytes), _) => {
            ui.label(format!("{} {bytes}", words.servo().project_needs));
        }
        (Err(error), _) => {
            ui.colored_label(ui.visuals().error_fg_color, error);
        }
    }
    ui.add_space(6.0);
    let idle = view.operation.is_none() && view.pending.is_none();
    ui.horizontal(|ui| {
        ui.add_enabled_ui(view.connected && idle, |ui| {
            if ui.button(words.servo().upload_to_board).on_hover_text(words.upload_hint).clicked() {
                actions.push(Action::family(ServoAction::BoardCompare(BoardIntent::Upload)));
            }
            if ui.button(words.servo().read_board).on_hover_text(words.servo().read_hint).clicked() {
                actions.push(Action::family(ServoAction::BoardCompare(BoardIntent::ReadIntoProject)));
            }
            // The shell asks where, off the frame; the answer comes back as a comparison.
            if ui.button(words.export_board).clicked() {
                actions.push(Action::AskFile(FileRequest::Export(Export::json("board.json", PROJECT_FILE, |path| {
                    Action::family(ServoAction::BoardCompare(BoardIntent::ExportToFile(path)))
                }))));
            }
        });
    });
    if !view.connected {
        ui.label(words.connect_to_transfer);
    }

    if let Some(operation) = view.operation {
        running(ui, operation, language, actions);
    }
    if let Some(pending) = view.pending {
        confirming(ui, pending, language, actions);
    }
    if let Some(result) = view.result {
        outcome(ui, result, (view.connected && idle, language), actions);
    }
}

/// The running operation: what it does, how far it is, Cancel.
fn running(
    ui: &mut egui::Ui,
    operation: &super::operations::ServoOperation,
    language: Language,
    actions: &mut Vec<Action>,
) {
    let words = language.strings();
    ui.separator();
    let what = match operation.kind {
        ServoKind::Compare => words.servo().reading_to_compare,
        ServoKind::Upload { .. } => words.servo().uploading,
    };
    ui.label(what);
    if let Some(progress) = &operation.progress {
        let item = progress.item.worded(language);
        ui.add(
            egui::ProgressBar::new(operation.fraction())
                .show_percentage()
                .text(format!("{}/{} {item}", progress.done, progress.total)),
        );
    }
    if ui.button(words.cancel).clicked() {
        actions.push(Action::CancelOperation);
    }
}

/// A comparison waiting for confirmation: its differences, Confirm and Cancel.
fn confirming(ui: &mut egui::Ui, pending: &PendingConfirm, language: Language, actions: &mut Vec<Action>) {
    let words = language.strings();
    ui.separator();
    let differences = difference_lines(pending, language);
    if differences.is_empty() {
        ui.label(words.servo().already_identical);
    } else {
        ui.label(format!("{} {}", differences.len(), words.servo().differences));
        let row_height = ui.text_style_height(&egui::TextStyle::Monospace);
        let height = (ui.available_height() * 0.5).max(row_height * 4.0);
        rows::list(ui, "differences", row_height, differences.len(), height, |ui, index| {
            ui.monospace(&differences[index]);
        });
    }
    ui.horizontal(|ui| {
        let confirm = match &pending.intent {
            BoardIntent::Upload | BoardIntent::UploadAnyway => words.servo().confirm_upload,
            BoardIntent::ReadIntoProject => words.confirm_read,
            BoardIntent::ExportToFile(_) => words.servo().confirm_export,
        };
        if ui.button(confirm).clicked() {
            actions.push(Action::family(ServoAction::BoardConfirm));
        }
        if ui.button(words.cancel).clicked() {
            actions.push(Action::family(ServoAction::BoardDismiss));
        }
    });
}

/// The last outcome: what was done or went wrong, and the items it went through.
fn outcome(
    ui: &mut egui::Ui,
    result: &BoardResult,
    (can_upload, language): (bool, Language),
    actions: &mut Vec<Action>,
) {
    let words = language.strings();
    ui.separator();
    if let Some(error) = result.error_text(language) {
        ui.colored_label(ui.visuals().error_fg_color, error);
    }
    let items: &[Item] = match result {
        BoardResult::Uploaded { items, backup, curves } => {
            ui.label(format!("{} {}", words.uploaded_items, items.len()));
            if let Some(backup) = backup {
                ui.label(format!("{} {}", words.backup_at, backup.display()));
            }
            if let Some(curves) = curves {
                let captions = words.servo();
                let deviation = f64::from(curves.max_error_tenths) / 10.0;
                ui.label(format!("{} {deviation:.1}°", captions.curves_stored));
                if curves.widened() {
                    let tolerance = f64::from(curves.tolerance_tenths) / 10.0;
                    ui.colored_label(
                        ui.visuals().warn_fg_color,
                        format!("{} → {tolerance:.1}°", captions.tolerance_widened),
                    );
                }
            }
            items.as_slice()
        }
        BoardResult::Invalid { .. } => {
            let anyway = ui.add_enabled(can_upload, egui::Button::new(words.servo().upload_anyway));
            if anyway.on_hover_text(words.servo().upload_anyway_hint).clicked() {
                actions.push(Action::family(ServoAction::BoardCompare(BoardIntent::UploadAnyway)));
            }
            &[]
        }
        BoardResult::Failed { items, .. } => items.as_slice(),
        BoardResult::ReadIntoProject => {
            ui.label(words.read_done);
            &[]
        }
        BoardResult::Exported(path) => {
            ui.label(format!("{} {}", words.saved_board_to, path.display()));
            &[]
        }
        BoardResult::ExportFailed(_) => &[],
        BoardResult::Cancelled => {
            ui.label(words.cancelled);
            &[]
        }
    };
    if !items.is_empty() {
        // The rest of the panel's height: the list fills it.
        let row_height = ui.text_style_height(&egui::TextStyle::Body);
        rows::list(ui, "items", row_height, items.len(), ui.available_height(), |ui, index| {
            ui.label(format!("√ {}", items[index].worded(language)));
        });
    }
}

#[cfg(test)]
mod tests {
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable;

    use super::*;
    use crate::device::servo::Difference;
    use crate::ui::i18n::Language;

    /// With 500 differences waiting and 500 items uploaded, only the rows in
    /// view of each list are laid out.
    #[test]
    fn the_difference_and_item_lists_lay_out_the_rows_in_view() {
        use crate::device::servo::RecordKind;
        let pending = PendingConfirm {
            intent: BoardIntent::Upload,
            differences: Ok((0..500).map(|id| Difference::Missing { kind: RecordKind::Action, id }).collect()),
        };
        let result = BoardResult::Uploaded {
            items: (0..500).map(|id| Item::Action { id, caption: format!("uploaded {id}") }).collect(),
            backup: None,
            curves: None,
        };
        let mut harness =
            Harness::builder().with_size(egui::vec2(1000.0, 800.0)).with_accessibility_check(false).build_ui(|panel| {
                let view = BoardView {
                    connected: true,
                    project_bytes: Ok(1000),
                    board_total_bytes: Some(60_000),
                    operation: None,
                    pending: Some(&pending),
                    result: Some(&result),
                };
                let mut actions = Vec::new();
                ui(panel, &view, Language::English, &mut actions);
            });
        harness.run_steps(3);
        for needle in ["missing on the board", "uploaded "] {
            let laid_out = harness.query_all_by_label_contains(needle).count();
            // Neither list can show more than the 800-pixel window holds.
            assert!((3..=60).contains(&laid_out), "{needle}: {laid_out} of 500 rows laid out");
        }
    }
}
