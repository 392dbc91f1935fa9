//! Long board operations on a worker thread, so the window never freezes:
//! progress and the outcome come back over channels, and a cancel message
//! stops the operation between two steps.

use std::path::PathBuf;

use crossbeam_channel::{Receiver, Sender};

use crate::device::Cancel;
use crate::device::servo::{
    ImportOptions, ImportReport, Phase, Progress, Requester, ServoImage, export, import, read_image,
};
use crate::link::Waker;
use crate::project::ServoProject;

/// What a job does.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum JobKind {
    /// Read the board and compare it with the project.
    Compare,
    /// Write the project onto the board (with backup and verification);
    /// `force` writes even with validation errors (Upload anyway).
    Upload {
        /// Write despite validation errors.
        force: bool,
    },
    /// Read the board into a project.
    Read,
}

/// How a job ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum JobOutcome {
    /// The board was read and compared: what differs, and what it holds.
    Compared {
        /// Differences, project first (empty = identical).
        differences: Vec<String>,
        /// The board's contents.
        board: Box<ServoProject>,
    },
    /// The project was written and verified.
    Uploaded(ImportReport),
    /// The board was read.
    Read(Box<ServoProject>),
    /// The operation failed; the text says what and what to try.
    Failed(String),
    /// The user cancelled.
    Cancelled,
}

/// A running job.
#[derive(Debug)]
pub struct Job {
    /// What it does.
    pub kind: JobKind,
    /// The latest progress.
    pub progress: Option<Progress>,
    /// Every item finished so far, in order, with the phase it belonged to.
    pub done_items: Vec<(Phase, crate::device::servo::Item)>,
    progress_rx: Receiver<Progress>,
    outcome_rx: Receiver<JobOutcome>,
    cancel: Sender<()>,
}

impl Job {
    /// Starts `kind` on a worker thread. `waker` is called after each step.
    pub fn start(
        kind: JobKind,
        requester: Requester,
        project: ServoProject,
        backup_dir: PathBuf,
        language: crate::ui::i18n::Language,
        waker: Waker,
    ) -> Self {
        let (progress_tx, progress_rx) = crossbeam_channel::unbounded();
        let (outcome_tx, outcome_rx) = crossbeam_channel::bounded(1);
        let (cancel, token) = Cancel::new();
        let job_kind = kind.clone();
        let worker_waker = waker;
        let spawned = std::thread::Builder::new().name("board job".into()).spawn(move || {
            let mut report = |progress: &Progress| {
                let _ = progress_tx.send(progress.clone());
                worker_waker();
            };
            let outcome = run(&job_kind, &requester, &project, backup_dir, language, &mut report, &token);
            let _ = outcome_tx.send(outcome);
            worker_waker();
        });
        if let Err(error) = spawned {
            // No thread: report it as the job's outcome.
            let (tx, rx) = crossbeam_channel::bounded(1);
            let _ = tx.send(JobOutcome::Failed(format!("cannot start the operation: {error}")));
            return Self { kind, progress: None, done_items: Vec::new(), progress_rx, outcome_rx: rx, cancel };
        }
        Self { kind, progress: None, done_items: Vec::new(), progress_rx, outcome_rx, cancel }
    }

    /// Asks the job to stop after its current step.
    pub fn cancel(&self) {
        let _ = self.cancel.try_send(());
    }

    /// Takes in progress; returns the outcome once the job has ended.
    pub fn poll(&mut self) -> Option<JobOutcome> {
        for progress in self.progress_rx.try_iter() {
            let finished_one =
                self.progress.as_ref().is_none_or(|last| progress.done > last.done || progress.phase != last.phase);
            if finished_one && progress.done > 0 {
                self.done_items.push((progress.phase, progress.item.clone()));
            }
            self.progress = Some(progress);
        }
        self.outcome_rx.try_recv().ok()
    }
}

fn run(
    kind: &JobKind,
    requester: &Requester,
    project: &ServoProject,
    backup_dir: PathBuf,
    language: crate::ui::i18n::Language,
    report: &mut dyn FnMut(&Progress),
    cancel: &Cancel,
) -> JobOutcome {
    let failed = |error: crate::device::servo::OpError| match error {
        crate::device::servo::OpError::Cancelled => JobOutcome::Cancelled,
        other => JobOutcome::Failed(language.op_error(&other)),
    };
    match kind {
        JobKind::Compare => match read_image(requester, report, cancel) {
            Ok(board) => {
                let differences = match ServoImage::from_project(project) {
                    Ok(ours) => ours.differences(&board).iter().map(|d| language.difference(d)).collect(),
                    Err(error) => vec![language.op_error(&crate::device::servo::OpError::Image(error))],
                };
                JobOutcome::Compared { differences, board: Box::new(board.to_project()) }
            }
            Err(error) => failed(error),
        },
        JobKind::Upload { force } => {
            if let Err(error) = std::fs::create_dir_all(&backup_dir) {
                return JobOutcome::Failed(language.backup_folder_failed(&backup_dir, &error));
            }
            let options = ImportOptions { backup_dir: Some(backup_dir), verify: true, force: *force };
            match import(requester, project, &options, report, cancel) {
                Ok(done) => JobOutcome::Uploaded(done),
                Err(failure) if matches!(failure.error, crate::device::servo::OpError::Cancelled) => {
                    JobOutcome::Cancelled
                }
                Err(failure) => JobOutcome::Failed(language.upload_failure(&failure)),
            }
        }
        JobKind::Read => match export(requester, report, cancel) {
            Ok(board) => JobOutcome::Read(Box::new(board)),
            Err(error) => failed(error),
        },
    }
}
