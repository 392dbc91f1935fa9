//! A PLEN2 operation — reading the robot, uploading, writing joint
//! settings, a factory reset — run off the frame: what it is, how it ends,
//! and what the robot panel says of it.

use std::path::PathBuf;

use crate::device::plen2::{self, Command, Plen2ImportFailure, Plen2ImportOptions, Plen2ImportReport, Plen2OpError};
use crate::device::plen2::{Plen2Item, ReplyError};
use crate::project::plen2::{Plen2Project, SLOTS};
use crate::ui::operation::{Operation, Step};

/// A PLEN2 operation as it runs.
pub type Plen2Operation = Operation<Plen2Kind, Plen2Outcome, Plen2Item>;

/// What a PLEN2 operation does.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Plen2Kind {
    /// Read the version, the joint settings and all 90 slots.
    Read,
    /// Upload motions (and joint settings the project holds), backing up first and verifying.
    Upload,
    /// Write the project's joint settings where they differ.
    WriteJoints,
    /// Factory joint settings.
    FactoryReset,
}

/// Why a PLEN2 operation failed.
#[derive(Debug)]
pub enum Plen2Failure {
    /// A step failed.
    Op(Plen2OpError),
    /// An upload failed, leaving what it says.
    Upload(Box<Plen2ImportFailure>),
    /// A command could not be sent.
    Reply(ReplyError),
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

/// How a PLEN2 operation ended.
#[derive(Debug)]
pub enum Plen2Outcome {
    /// The robot was read.
    Read(Box<Plen2Project>),
    /// The upload's per-slot report.
    Uploaded(Plen2ImportReport),
    /// Joint settings written (how many commands).
    JointsWritten(usize),
    /// Failed.
    Failed(Plen2Failure),
    /// The user cancelled.
    Cancelled,
}

/// What the robot panel says after an operation (worded when shown).
#[derive(Debug)]
pub enum Plen2Result {
    /// The robot was read: how many motions it holds.
    Read(usize),
    /// The upload's report.
    Uploaded(Plen2ImportReport),
    /// Joint settings written.
    JointsWritten(usize),
    /// The project has errors; nothing was written.
    Invalid(crate::project::Problems),
    /// What the robot held replaced the project's PLEN2 section.
    ReadIntoProject,
    /// What the robot held was saved to this file.
    Exported(PathBuf),
    /// The file could not be written; why.
    ExportFailed(String),
    /// It failed.
    Failed(Plen2Failure),
    /// The user cancelled.
    Cancelled,
}

pub fn run(
    kind: &Plen2Kind,
    requester: &plen2::Plen2Requester,
    project: &Plen2Project,
    backups: PathBuf,
    report: &mut dyn FnMut(Step<Plen2Item>),
    cancel: &crate::device::Cancel,
) -> Plen2Outcome {
    let mut progress = |step: &plen2::Plen2Progress| report(step.clone());
    let failed = |error: Plen2OpError| match error {
        Plen2OpError::Cancelled => Plen2Outcome::Cancelled,
        other => Plen2Outcome::Failed(Plen2Failure::Op(other)),
    };
    match kind {
        Plen2Kind::Read => {
            let slots: Vec<u8> = (0..SLOTS).collect();
            match plen2::export(requester, &slots, &mut progress, cancel) {
                Ok(project) => Plen2Outcome::Read(Box::new(project)),
                Err(error) => failed(error),
            }
        }
        Plen2Kind::Upload => {
            if let Err(error) = std::fs::create_dir_all(&backups) {
                return Plen2Outcome::Failed(Plen2Failure::BackupFolder { folder: backups, error });
            }
            let options = Plen2ImportOptions { backup_dir: Some(backups), verify: true, force: false };
            match plen2::import(requester, project, &options, &mut progress, cancel) {
                Ok(done) => Plen2Outcome::Uploaded(done),
                // Cancelled before a byte was written: nothing to say but that; after, what it left.
                Err(failure)
                    if matches!(failure.error, Plen2OpError::Cancelled)
                        && matches!(failure.left, crate::device::Left::Untouched) =>
                {
                    Plen2Outcome::Cancelled
                }
                Err(failure) => Plen2Outcome::Failed(Plen2Failure::Upload(failure)),
            }
        }
        Plen2Kind::WriteJoints => {
            let written = plen2::read_joint_settings(requester)
                .and_then(|current| plen2::write_joint_settings(requester, &project.joints, &current));
            match written {
                Ok(count) => Plen2Outcome::JointsWritten(count),
                Err(error) => failed(error),
            }
        }
        Plen2Kind::FactoryReset => match requester.send_and_wait(Command::ResetJoints) {
            Ok(()) => Plen2Outcome::JointsWritten(1),
            Err(error) => Plen2Outcome::Failed(Plen2Failure::Reply(error)),
        },
    }
}
