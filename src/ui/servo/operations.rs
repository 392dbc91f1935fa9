//! Board operations from the board panel: compare first, then upload (or
//! upload anyway), read into the project, or export to a file, on the shared
//! operation runner. Outcomes stay typed until the panel words them.

use std::path::PathBuf;

use super::ServoUi;
use super::board::{BoardResult, PendingConfirm};
use crate::device::servo::{
    Difference, ImageError, ImportFailure, ImportOptions, ImportReport, OpError, ServoImage, import, read_image,
};
use crate::project::{Edit, Project, ServoProject, has_errors, validate_servo};
use crate::ui::action::BoardIntent;
use crate::ui::app::{RunningOperation, Shell};
use crate::ui::operation::{Operation, Step, Subject};

/// What a servo board operation does.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ServoKind {
    /// Read the board and compare it with the project.
    Compare,
    /// Write the project onto the board (with backup and verification);
    /// `force` writes even with validation errors (Upload anyway).
    Upload {
        /// Write despite validation errors.
        force: bool,
    },
}

/// Why a servo board operation failed.
#[derive(Debug)]
pub enum ServoFailure {
    /// A step failed.
    Op(OpError),
    /// An upload failed, leaving what it says.
    Upload(Box<ImportFailure>),
    /// The backup folder could not be made; nothing was written.
    BackupFolder {
        /// The folder.
        folder: PathBuf,
        /// Why.
        error: std::io::Error,
    },
    /// No worker thread could start.
    Thread(std::io::Error),
}

/// How a servo board operation ended.
#[derive(Debug)]
pub enum ServoOutcome {
    /// The board was read and compared: what differs (or why the project
    /// cannot be put in board records), and what it holds.
    Compared {
        /// Differences, project first (empty = identical).
        differences: Result<Vec<Difference>, ImageError>,
        /// The board's contents.
        board: Box<ServoProject>,
    },
    /// The project was written and verified.
    Uploaded(ImportReport),
    /// The operation failed.
    Failed(ServoFailure),
    /// The user cancelled.
    Cancelled,
}

fn run(
    kind: &ServoKind,
    requester: &crate::device::servo::Requester,
    project: &ServoProject,
    backups: PathBuf,
    report: &mut dyn FnMut(Step),
    cancel: &crate::device::Cancel,
) -> ServoOutcome {
    let mut progress = |step: &crate::device::servo::Progress| {
        report(Step { phase: step.phase, done: step.done, total: step.total, item: Subject::Servo(step.item.clone()) });
    };
    match kind {
        ServoKind::Compare => match read_image(requester, &mut progress, cancel) {
            Ok(board) => {
                let differences = ServoImage::from_project(project).map(|ours| ours.differences(&board));
                ServoOutcome::Compared { differences, board: Box::new(board.to_project()) }
            }
            Err(OpError::Cancelled) => ServoOutcome::Cancelled,
            Err(error) => ServoOutcome::Failed(ServoFailure::Op(error)),
        },
        ServoKind::Upload { force } => {
            if let Err(error) = std::fs::create_dir_all(&backups) {
                return ServoOutcome::Failed(ServoFailure::BackupFolder { folder: backups, error });
            }
            let options = ImportOptions { backup_dir: Some(backups), verify: true, force: *force };
            match import(requester, project, &options, &mut progress, cancel) {
                Ok(done) => ServoOutcome::Uploaded(done),
                // Cancelled before a byte was written: nothing to say but that; after, what it left.
                Err(failure)
                    if matches!(failure.error, OpError::Cancelled)
                        && matches!(failure.left, crate::device::Left::Untouched) =>
                {
                    ServoOutcome::Cancelled
                }
                Err(failure) => ServoOutcome::Failed(ServoFailure::Upload(failure)),
            }
        }
    }
}

impl ServoUi {
    fn start(&mut self, shell: &mut Shell<'_>, kind: ServoKind) {
        let Some(link) = shell.servo() else {
            shell.report(shell.words().msg_connect_first, true);
            return;
        };
        let requester = link.requester();
        self.board_result = None;
        let backups = shell.data_dir.join("backups");
        let project = shell.document.project.servo.clone();
        let job_kind = kind.clone();
        let operation = Operation::start(
            kind,
            shell.waker.clone(),
            move |report, cancel| run(&job_kind, &requester, &project, backups, report, cancel),
            |error| ServoOutcome::Failed(ServoFailure::Thread(error)),
        );
        *shell.operation = Some(RunningOperation::Servo(operation));
    }

    pub(super) fn board_compare(&mut self, shell: &mut Shell<'_>, intent: BoardIntent) {
        if shell.operation.is_some() {
            return;
        }
        if intent == BoardIntent::Upload {
            let problems = validate_servo(&shell.document.project.servo);
            if has_errors(&problems) {
                self.board_result = Some(BoardResult::Invalid { problems: problems.errors_only() });
                return;
            }
        }
        self.compare_intent = Some(intent);
        self.start(shell, ServoKind::Compare);
    }

    pub(super) fn board_confirm(&mut self, shell: &mut Shell<'_>) {
        let Some(pending) = self.pending.take() else { return };
        let board = self.compared_board.take().unwrap_or_default();
        match pending.intent {
            BoardIntent::Upload => self.start(shell, ServoKind::Upload { force: false }),
            BoardIntent::UploadAnyway => self.start(shell, ServoKind::Upload { force: true }),
            BoardIntent::ReadIntoProject => {
                // The board does not store the client-side safety limits and the
                // rig: keep the project's for servos it already knows.
                let mut board = board;
                for servo in &mut board.servos {
                    if let Some(known) = shell.document.project.servo.servo(servo.id) {
                        servo.min_deg = known.min_deg;
                        servo.max_deg = known.max_deg;
                        servo.home_deg = known.home_deg;
                        servo.rig = known.rig;
                    }
                }
                self.pose = super::homes(&board);
                shell.document.apply(Edit::ReplaceAll(Box::new(board)), None);
                self.board_result = Some(BoardResult::ReadIntoProject);
            }
            BoardIntent::ExportToFile(path) => {
                self.board_result = Some(match crate::project::save(&path, &Project::servo(board)) {
                    Ok(()) => BoardResult::Exported(path),
                    Err(error) => BoardResult::ExportFailed(error.to_string()),
                });
            }
        }
    }

    /// The family's operation ended: what it found, for the panel.
    pub fn finish(&mut self, operation: &Operation<ServoKind, ServoOutcome>, outcome: ServoOutcome) {
        let written: Vec<crate::device::servo::Item> = operation
            .done_items
            .iter()
            .filter(|(phase, _)| *phase == crate::device::Phase::Write)
            .filter_map(|(_, item)| match item {
                Subject::Servo(item) => Some(item.clone()),
                Subject::Plen2(_) => None,
            })
            .collect();
        match outcome {
            ServoOutcome::Compared { differences, board } => {
                if let Some(intent) = self.compare_intent.take() {
                    self.pending = Some(PendingConfirm { intent, differences });
                    self.compared_board = Some(*board);
                }
            }
            ServoOutcome::Uploaded(report) => {
                self.board_result = Some(BoardResult::Uploaded { items: written, backup: report.backup });
            }
            ServoOutcome::Failed(failure) => {
                self.board_result = Some(BoardResult::Failed { items: written, failure: std::sync::Arc::new(failure) });
            }
            ServoOutcome::Cancelled => self.board_result = Some(BoardResult::Cancelled),
        }
    }
}
