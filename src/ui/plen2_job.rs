//! PLEN2 robot operations on a worker thread: read every slot, upload with
//! backup and verification, write joint settings, factory reset. Progress and
//! the outcome come back over channels; Cancel stops between two slots.

use std::path::PathBuf;

use crossbeam_channel::{Receiver, Sender};

use crate::device::Cancel;
use crate::device::plen2::Command;
use crate::device::plen2::{self, Plen2ImportOptions, Plen2ImportReport, Plen2Progress, Plen2Requester};
use crate::link::Waker;
use crate::project::plen2::Plen2Project;
use crate::project::plen2::SLOTS;

/// What a PLEN2 job does.
#[derive(Clone, Debug, PartialEq)]
pub enum Plen2JobKind {
    /// Read the version, the joint settings and all 90 slots.
    Read,
    /// Upload motions (and joint settings the project holds), backing up first and verifying.
    Upload(Box<Plen2Project>),
    /// Write the project's joint settings where they differ.
    WriteJoints(Box<Plen2Project>),
    /// Factory joint settings.
    FactoryReset,
}

/// How a PLEN2 job ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Plen2Outcome {
    /// The robot was read.
    Read(Box<Plen2Project>),
    /// The upload's per-slot report.
    Uploaded(Plen2ImportReport),
    /// Joint settings written (how many commands).
    JointsWritten(usize),
    /// Failed; the text says what and what to try.
    Failed(String),
    /// The user cancelled.
    Cancelled,
}

/// A running PLEN2 job.
#[derive(Debug)]
pub struct Plen2Job {
    /// The latest progress.
    pub progress: Option<Plen2Progress>,
    progress_rx: Receiver<Plen2Progress>,
    outcome_rx: Receiver<Plen2Outcome>,
    cancel: Sender<()>,
}

fn run(
    kind: Plen2JobKind,
    requester: &Plen2Requester,
    backups: PathBuf,
    report: &mut dyn FnMut(&Plen2Progress),
    cancel: &Cancel,
) -> Plen2Outcome {
    let failed = |error: plen2::Plen2OpError| match error {
        plen2::Plen2OpError::Cancelled => Plen2Outcome::Cancelled,
        other => Plen2Outcome::Failed(other.to_string()),
    };
    match kind {
        Plen2JobKind::Read => {
            let slots: Vec<u8> = (0..SLOTS).collect();
            match plen2::export(requester, &slots, report, cancel) {
                Ok(project) => Plen2Outcome::Read(Box::new(project)),
                Err(error) => failed(error),
            }
        }
        Plen2JobKind::Upload(project) => {
            if let Err(error) = std::fs::create_dir_all(&backups) {
                return Plen2Outcome::Failed(format!(
                    "cannot create the backup folder {}: {error}; nothing was written",
                    backups.display()
                ));
            }
            let options = Plen2ImportOptions { backup_dir: Some(backups), verify: true, force: false };
            match plen2::import(requester, &project, &options, report, cancel) {
                Ok(done) => Plen2Outcome::Uploaded(done),
                Err(failure) if matches!(failure.error, plen2::Plen2OpError::Cancelled) => Plen2Outcome::Cancelled,
                Err(failure) => Plen2Outcome::Failed(failure.to_string()),
            }
        }
        Plen2JobKind::WriteJoints(project) => {
            let written = plen2::read_joint_settings(requester)
                .and_then(|current| plen2::write_joint_settings(requester, &project.joints, &current));
            match written {
                Ok(count) => Plen2Outcome::JointsWritten(count),
                Err(error) => failed(error),
            }
        }
        Plen2JobKind::FactoryReset => match requester.send_and_wait(Command::ResetJoints) {
            Ok(()) => Plen2Outcome::JointsWritten(1),
            Err(error) => Plen2Outcome::Failed(error.to_string()),
        },
    }
}

impl Plen2Job {
    /// Starts `kind` on a worker thread; `waker` is called after each step.
    pub fn start(kind: Plen2JobKind, requester: Plen2Requester, backups: PathBuf, waker: Waker) -> Self {
        let (progress_tx, progress_rx) = crossbeam_channel::unbounded();
        let (outcome_tx, outcome_rx) = crossbeam_channel::bounded(1);
        let (cancel, token) = Cancel::new();
        let spawned = std::thread::Builder::new().name("plen2 job".into()).spawn(move || {
            let mut report = |progress: &Plen2Progress| {
                let _ = progress_tx.send(progress.clone());
                waker();
            };
            let outcome = run(kind, &requester, backups, &mut report, &token);
            let _ = outcome_tx.send(outcome);
            waker();
        });
        if let Err(error) = spawned {
            let (tx, rx) = crossbeam_channel::bounded(1);
            let _ = tx.send(Plen2Outcome::Failed(format!("cannot start the operation: {error}")));
            return Self { progress: None, progress_rx, outcome_rx: rx, cancel };
        }
        Self { progress: None, progress_rx, outcome_rx, cancel }
    }

    /// Asks the job to stop between two slots.
    pub fn cancel(&self) {
        let _ = self.cancel.try_send(());
    }

    /// Takes in progress; the outcome once the job has ended.
    pub fn poll(&mut self) -> Option<Plen2Outcome> {
        if let Some(last) = self.progress_rx.try_iter().last() {
            self.progress = Some(last);
        }
        self.outcome_rx.try_recv().ok()
    }
}
