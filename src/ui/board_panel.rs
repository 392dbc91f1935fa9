//! The board panel: memory meter, upload to board, read board into project,
//! export board to file — each starts by reading the board and showing what
//! differs, and overwrites nothing until the user confirms.

use std::path::PathBuf;

use crate::ui::action::{Action, BoardIntent};
use crate::ui::job::{Job, JobKind};

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
pub fn ui(ui: &mut egui::Ui, view: &BoardView<'_>, actions: &mut Vec<Action>) {
    ui.heading("Board");
    match (&view.project_bytes, view.board_total_bytes) {
        (Ok(bytes), Some(total)) if total > 0 => {
            let fraction = *bytes as f32 / total as f32;
            let bar = egui::ProgressBar::new(fraction.min(1.0)).text(format!("project needs {bytes} of {total} bytes"));
            ui.add(bar.fill(if fraction > 1.0 { ui.visuals().error_fg_color } else { ui.visuals().selection.bg_fill }));
        }
        (Ok(bytes), _) => {
            ui.label(format!("project needs {bytes} bytes (connect to see the board's capacity)"));
        }
        (Err(error), _) => {
            ui.colored_label(ui.visuals().error_fg_color, error);
        }
    }
    ui.add_space(6.0);
    let idle = view.job.is_none() && view.pending.is_none();
    ui.horizontal(|ui| {
        ui.add_enabled_ui(view.connected && idle, |ui| {
            if ui
                .button("Upload to board")
                .on_hover_text("Compare, then back the board up, write, and verify")
                .clicked()
            {
                actions.push(Action::BoardCompare(BoardIntent::Upload));
            }
            if ui
                .button("Read board into project")
                .on_hover_text("Compare, then replace the project (undoable)")
                .clicked()
            {
                actions.push(Action::BoardCompare(BoardIntent::ReadIntoProject));
            }
            if ui.button("Export board to file…").clicked()
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
        ui.label("Connect a board (or the demo board) to upload or read.");
    }

    if let Some(job) = view.job {
        ui.separator();
        let what = match job.kind {
            JobKind::Compare => "Reading the board to compare",
            JobKind::Upload => "Uploading",
            JobKind::Read => "Reading the board",
        };
        ui.label(what);
        if let Some(progress) = &job.progress {
            let fraction = if progress.total == 0 { 0.0 } else { progress.done as f32 / progress.total as f32 };
            ui.add(
                egui::ProgressBar::new(fraction)
                    .show_percentage()
                    .text(format!("{:?} {}/{} {}", progress.phase, progress.done, progress.total, progress.item)),
            );
        }
        if ui.button("Cancel").clicked() {
            actions.push(Action::BoardCancel);
        }
    }

    if let Some(pending) = view.pending {
        ui.separator();
        if pending.differences.is_empty() {
            ui.label("The board already holds exactly this project.");
        } else {
            ui.label(format!("{} difference(s) between the project and the board:", pending.differences.len()));
            egui::ScrollArea::vertical().max_height(180.0).id_salt("differences").show(ui, |ui| {
                for difference in &pending.differences {
                    ui.monospace(difference);
                }
            });
        }
        ui.horizontal(|ui| {
            let confirm = match &pending.intent {
                BoardIntent::Upload => "Back up the board, then overwrite it",
                BoardIntent::ReadIntoProject => "Replace the project with the board",
                BoardIntent::ExportToFile(_) => "Save the board to the file",
            };
            if ui.button(confirm).clicked() {
                actions.push(Action::BoardConfirm);
            }
            if ui.button("Cancel").clicked() {
                actions.push(Action::BoardDismiss);
            }
        });
    }

    if let Some(result) = view.result {
        ui.separator();
        let items = match result {
            BoardResult::Uploaded { items, backup } => {
                ui.label(format!("Uploaded and verified {} item(s).", items.len()));
                if let Some(backup) = backup {
                    ui.label(format!("Backup of the previous contents: {}", backup.display()));
                }
                items.as_slice()
            }
            BoardResult::Failed { items, error } => {
                ui.colored_label(ui.visuals().error_fg_color, error);
                items.as_slice()
            }
            BoardResult::ReadIntoProject => {
                ui.label("The project now holds the board's contents (Undo brings the previous project back).");
                &[]
            }
            BoardResult::Exported(path) => {
                ui.label(format!("Saved the board to {}", path.display()));
                &[]
            }
            BoardResult::Cancelled => {
                ui.label("Cancelled.");
                &[]
            }
        };
        if !items.is_empty() {
            egui::ScrollArea::vertical().max_height(220.0).id_salt("items").show(ui, |ui| {
                for item in items {
                    ui.label(format!("√ {item}"));
                }
            });
        }
    }
}
