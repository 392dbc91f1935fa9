//! Board operations from the board panel: compare first, then upload (or
//! upload anyway), read into the project, or export to a file, on the shared
//! operation runner. Outcomes stay typed until the panel words them.

use std::path::PathBuf;

use std::sync::Arc;

use super::ServoLink;
use super::ServoUi;
use crate::device::servo::{
    Difference, ImageError, ImportFailure, ImportOptions, ImportReport, Item, OpError, ServoImage, import, read_image,
};
use crate::project::{Edit, Project, ServoProject, has_errors, validate_servo};
use crate::ui::i18n::Language;
use crate::ui::i18n::Worded;
use crate::ui::operation::{Operation, Step};
use crate::ui::servo::action::BoardIntent;
use crate::ui::shell::{RunningOperation, Shell};

/// A servo board operation as it runs.
pub type ServoOperation = Operation<ServoKind, ServoOutcome, Item>;

/// A comparison waiting for the user's go-ahead.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PendingConfirm {
    /// What happens on confirm.
    pub intent: BoardIntent,
    /// What differs between project and board (empty = identical), or why
    /// the project cannot be put in board records.
    pub differences: Result<Vec<Difference>, ImageError>,
}

/// The outcome shown after an operation.
#[derive(Clone, Debug)]
pub enum BoardResult {
    /// Written and verified.
    Uploaded {
        /// Each item written, in order.
        items: Vec<Item>,
        /// Where the board's previous contents were saved.
        backup: Option<PathBuf>,
        /// What baking the project's curves cost, if it had any.
        curves: Option<crate::device::servo::CurveCost>,
    },
    /// The project has authoring errors; nothing was written. The user may upload anyway.
    Invalid {
        /// The errors, with their locations.
        problems: crate::project::Problems,
    },
    /// Stopped with an error.
    Failed {
        /// Items finished before the failure.
        items: Vec<Item>,
        /// What failed (and what it left).
        failure: Arc<ServoFailure>,
    },
    /// The board replaced the project (undoable).
    ReadIntoProject,
    /// The board was saved to a file.
    Exported(PathBuf),
    /// The board could not be saved to the file; the text says why.
    ExportFailed(String),
    /// The user cancelled.
    Cancelled,
}

impl BoardResult {
    /// The failure or problems in `language`, if this is one.
    pub fn error_text(&self, language: Language) -> Option<String> {
        match self {
            Self::Invalid { problems } => Some(OpError::Invalid { problems: problems.clone() }.worded(language)),
            Self::Failed { failure, .. } => Some(failure.words(language)),
            Self::ExportFailed(text) => Some(text.clone()),
            _ => None,
        }
    }
}

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

impl ServoFailure {
    /// Why it failed, in `language`.
    pub fn words(&self, language: Language) -> String {
        match self {
            Self::Op(error) => error.worded(language),
            Self::Upload(failure) => {
                language.upload_failure(failure, |error| error.worded(language), |item| item.worded(language))
            }
            Self::BackupFolder { folder, error } => language.backup_folder_failed(folder, error),
            Self::Thread(error) => language.no_worker(error),
        }
    }
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
    report: &mut dyn FnMut(Step<Item>),
    cancel: &crate::device::Cancel,
) -> ServoOutcome {
    let mut progress = |step: &crate::device::servo::Progress| report(step.clone());
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
            shell.say(|language| language.strings().msg_connect_first, true);
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
        *shell.operation = Some(RunningOperation::new(operation));
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
                // rig: keep the project's for servos it already knows (and its meshes).
                let mut board = board;
                for servo in &mut board.servos {
                    if let Some(known) = shell.document.project.servo.servo(servo.id) {
                        servo.min_deg = known.min_deg;
                        servo.max_deg = known.max_deg;
                        servo.home_deg = known.home_deg;
                        servo.rig = known.rig;
                    }
                }
                board.meshes.clone_from(&shell.document.project.servo.meshes);
                self.pose = super::homes(&board);
                shell.document.apply(Edit::ReplaceAll(Box::new(board)), None);
                self.board_result = Some(BoardResult::ReadIntoProject);
            }
            BoardIntent::ExportToFile(path) => {
                // Written off the frame; the panel says how it went (tick).
                let done = shell.files.save(path.clone(), &Project::servo(board));
                self.exporting = Some((path, done));
            }
        }
    }

    /// The board's contents written to a file, once they are.
    pub(super) fn finish_export(&mut self, language: Language) {
        let Some((path, done)) = &self.exporting else { return };
        let Ok(result) = done.try_recv() else { return };
        self.board_result = Some(match result {
            Ok(()) => BoardResult::Exported(path.clone()),
            Err(error) => BoardResult::ExportFailed(language.save_error(&error)),
        });
        self.exporting = None;
    }

    /// The family's operation ended: what it found, for the panel.
    pub fn finish(&mut self, operation: &ServoOperation, outcome: ServoOutcome) {
        let written: Vec<Item> = operation
            .done_items
            .iter()
            .filter(|(phase, _)| *phase == crate::device::Phase::Write)
            .map(|(_, item)| item.clone())
            .collect();
        match outcome {
            ServoOutcome::Compared { differences, board } => {
                if let Some(intent) = self.compare_intent.take() {
                    self.pending = Some(PendingConfirm { intent, differences });
                    self.compared_board = Some(*board);
                }
            }
            ServoOutcome::Uploaded(report) => {
                let (backup, curves) = (report.backup, report.curves);
                self.board_result = Some(BoardResult::Uploaded { items: written, backup, curves });
            }
            ServoOutcome::Failed(failure) => {
                self.board_result = Some(BoardResult::Failed { items: written, failure: Arc::new(failure) });
            }
            ServoOutcome::Cancelled => self.board_result = Some(BoardResult::Cancelled),
        }
    }
}
