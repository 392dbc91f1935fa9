//! The board panel: memory meter, upload to board, read board into project,
//! export board to file — each starts by reading the board and showing what
//! differs, and overwrites nothing until the user confirms.

use std::path::PathBuf;

use crate::ui::action::{Action, BoardIntent};
use crate::ui::job::{Job, JobKind};
use crate::ui::rows;

/// A comparison waiting for the user's go-ahead.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PendingConfirm {
    /// What happens on confirm.
    pub intent: BoardIntent,
    /// What differs between project and board (empty = identical).
    pub differences: Vec<String>,
}

/// The outcome shown after an operation.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BoardResult {
    /// Written and verified.
    Uploaded {
        /// Each item written, in order.
        items: Vec<String>,
        /// Where the board's previous contents were saved.
        backup: Option<PathBuf>,
    },
    /// The project has authoring errors; nothing was written. The user may upload anyway.
    Invalid {
        /// The problems, with their locations.
        error: String,
    },
    /// Stopped with an error.
    Failed {
        /// Items finished before the failure.
        items: Vec<String>,
        /// What failed and what to try.
        error: String,
    },
    /// The board replaced the project (undoable).
    ReadIntoProject,
    /// The board was saved to a file.
    Exported(PathBuf),
    /// The user cancelled.
    Cancelled,
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
    /// The running job.
    pub job: Option<&'a Job>,
    /// A comparison waiting for confirmation.
    pub pending: Option<&'a PendingConfirm>,
    /// The last outcome.
    pub result: Option<&'a BoardResult>,
}

/// Draws the board panel.
pub fn ui(ui: &mut egui::Ui, view: &BoardView<'_>, words: &crate::ui::i18n::Strings, actions: &mut Vec<Action>) {
    ui.heading(words.board);
    match (&view.project_bytes, view.board_total_bytes) {
        (Ok(bytes), Some(total)) if total > 0 => {
            let fraction = *bytes as f32 / total as f32;
            let bar = egui::ProgressBar::new(fraction.min(1.0))
                .text(format!("{} {bytes} {} {total}", words.project_needs, words.of_capacity));
            ui.add(bar.fill(if fraction > 1.0 { ui.visuals().error_fg_color } else { ui.visuals().selection.bg_fill }));
        }
        (Ok(bytes), _) => {
            ui.label(format!("{} {bytes}", words.project_needs));
        }
        (Err(error), _) => {
            ui.colored_label(ui.visuals().error_fg_color, error);
        }
    }
    ui.add_space(6.0);
    let idle = view.job.is_none() && view.pending.is_none();
    ui.horizontal(|ui| {
        ui.add_enabled_ui(view.connected && idle, |ui| {
            if ui.button(words.upload_to_board).on_hover_text(words.upload_hint).clicked() {
                actions.push(Action::BoardCompare(BoardIntent::Upload));
            }
            if ui.button(words.read_board).on_hover_text(words.read_hint).clicked() {
                actions.push(Action::BoardCompare(BoardIntent::ReadIntoProject));
            }
            if ui.button(words.export_board).clicked()
                && let Some(path) = rfd::FileDialog::new()
                    .add_filter("Servo Studio project", &["json"])
                    .set_file_name("board.json")
                    .save_file()
            {
                actions.push(Action::BoardCompare(BoardIntent::ExportToFile(path)));
            }
        });
    });
    if !view.connected {
        ui.label(words.connect_to_transfer);
    }

    if let Some(job) = view.job {
        ui.separator();
        let what = match job.kind {
            JobKind::Compare => words.reading_to_compare,
            JobKind::Upload { .. } => words.uploading,
            JobKind::Read => words.reading_board,
        };
        ui.label(what);
        if let Some(progress) = &job.progress {
            let fraction = if progress.total == 0 { 0.0 } else { progress.done as f32 / progress.total as f32 };
            ui.add(egui::ProgressBar::new(fraction).show_percentage().text(format!(
                "{}/{} {}",
                progress.done,
                progress.total,
                words.lang.item(&progress.item)
            )));
        }
        if ui.button(words.cancel).clicked() {
            actions.push(Action::BoardCancel);
        }
    }

    if let Some(pending) = view.pending {
        ui.separator();
        if pending.differences.is_empty() {
            ui.label(words.already_identical);
        } else {
            ui.label(format!("{} {}", pending.differences.len(), words.differences));
            let row_height = ui.text_style_height(&egui::TextStyle::Monospace);
            rows::list(ui, "differences", row_height, pending.differences.len(), 180.0, |ui, index| {
                ui.monospace(&pending.differences[index]);
            });
        }
        ui.horizontal(|ui| {
            let confirm = match &pending.intent {
                BoardIntent::Upload | BoardIntent::UploadAnyway => words.confirm_upload,
                BoardIntent::ReadIntoProject => words.confirm_read,
                BoardIntent::ExportToFile(_) => words.confirm_export,
            };
            if ui.button(confirm).clicked() {
                actions.push(Action::BoardConfirm);
            }
            if ui.button(words.cancel).clicked() {
                actions.push(Action::BoardDismiss);
            }
        });
    }

    if let Some(result) = view.result {
        ui.separator();
        let items = match result {
            BoardResult::Uploaded { items, backup } => {
                ui.label(format!("{} {}", words.uploaded_items, items.len()));
                if let Some(backup) = backup {
                    ui.label(format!("{} {}", words.backup_at, backup.display()));
                }
                items.as_slice()
            }
            BoardResult::Invalid { error } => {
                ui.colored_label(ui.visuals().error_fg_color, error);
                let anyway = ui.add_enabled(view.connected && idle, egui::Button::new(words.upload_anyway));
                if anyway.on_hover_text(words.upload_anyway_hint).clicked() {
                    actions.push(Action::BoardCompare(BoardIntent::UploadAnyway));
                }
                &[]
            }
            BoardResult::Failed { items, error } => {
                ui.colored_label(ui.visuals().error_fg_color, error);
                items.as_slice()
            }
            BoardResult::ReadIntoProject => {
                ui.label(words.read_done);
                &[]
            }
            BoardResult::Exported(path) => {
                ui.label(format!("{} {}", words.saved_board_to, path.display()));
                &[]
            }
            BoardResult::Cancelled => {
                ui.label(words.cancelled);
                &[]
            }
        };
        if !items.is_empty() {
            let row_height = ui.text_style_height(&egui::TextStyle::Body);
            rows::list(ui, "items", row_height, items.len(), 220.0, |ui, index| {
                ui.label(format!("√ {}", items[index]));
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable;

    use super::*;
    use crate::ui::i18n::Language;

    /// With 500 differences waiting and 500 items uploaded, only the rows in
    /// view of each list are laid out.
    #[test]
    fn the_difference_and_item_lists_lay_out_the_rows_in_view() {
        let pending = PendingConfirm {
            intent: BoardIntent::Upload,
            differences: (0..500).map(|n| format!("difference {n}")).collect(),
        };
        let result =
            BoardResult::Uploaded { items: (0..500).map(|n| format!("uploaded item {n}")).collect(), backup: None };
        let mut harness =
            Harness::builder().with_size(egui::vec2(1000.0, 800.0)).with_accessibility_check(false).build_ui(|panel| {
                let view = BoardView {
                    connected: true,
                    project_bytes: Ok(1000),
                    board_total_bytes: Some(60_000),
                    job: None,
                    pending: Some(&pending),
                    result: Some(&result),
                };
                let mut actions = Vec::new();
                ui(panel, &view, Language::English.strings(), &mut actions);
            });
        harness.run_steps(3);
        for (needle, height) in [("difference ", 180), ("uploaded item ", 220)] {
            let laid_out = harness.query_all_by_label_contains(needle).count();
            // A list `height` pixels tall shows about height ÷ 16 rows (plus one partly shown).
            let bound = height / 14 + 2;
            assert!((3..=bound).contains(&laid_out), "{needle}: {laid_out} of 500 rows laid out (bound {bound})");
        }
    }
}
