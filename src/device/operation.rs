//! What every family's long operation shares: a cancel token checked between
//! steps, where a backup goes, and — when an upload fails — what it left on
//! the device, said plainly (nothing written, some items, or everything).

use std::fmt;
use std::path::{Path, PathBuf};

use crossbeam_channel::{Receiver, Sender};

/// Which part of an operation is running.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Phase {
    /// Reading the device (an export, or the backup before an upload).
    Read,
    /// Writing onto the device.
    Write,
    /// Reading the device back to compare.
    Verify,
}

/// How far an operation has come; `I` names what it works on (the family's item).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Progress<I> {
    /// The part running.
    pub phase: Phase,
    /// Steps done in this part.
    pub done: usize,
    /// Steps this part has (it can grow as lists are read).
    pub total: usize,
    /// What is being done now, e.g. `action 3 "揮手"`.
    pub item: I,
}

/// Lets the owner stop an operation between two steps. Once asked, it stays
/// asked: every later check (and every clone) says so.
#[derive(Clone, Debug)]
pub struct Cancel {
    requested: Receiver<()>,
    asked: std::sync::Arc<std::sync::atomic::AtomicBool>,
}

impl Cancel {
    /// A cancel token and the sender that triggers it.
    pub fn new() -> (Sender<()>, Self) {
        let (sender, requested) = crossbeam_channel::bounded(1);
        (sender, Self { requested, asked: std::sync::Arc::default() })
    }

    /// A token that is never triggered.
    pub fn never() -> Self {
        Self { requested: crossbeam_channel::never(), asked: std::sync::Arc::default() }
    }

    /// Whether the owner asked to stop.
    pub fn is_requested(&self) -> bool {
        use std::sync::atomic::Ordering;
        if self.requested.try_recv().is_ok() {
            self.asked.store(true, Ordering::SeqCst);
        }
        self.asked.load(Ordering::SeqCst)
    }
}

/// Where a backup goes: `<stem>-YYYYMMDD-HHMMSS<tag>.json` in `folder` (local
/// time), with a counter if that name is taken.
pub fn backup_path(folder: &Path, stem: &str, tag: &str) -> PathBuf {
    let stamp = chrono::Local::now().format("%Y%m%d-%H%M%S");
    let base = format!("{stem}-{stamp}{tag}");
    let mut path = folder.join(format!("{base}.json"));
    let mut counter = 1;
    while path.exists() {
        counter += 1;
        path = folder.join(format!("{base}-{counter}.json"));
    }
    path
}

/// Which part of an upload was running when it failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Checking the project and the device (nothing read or written yet).
    Checking,
    /// Reading the device for the backup.
    BackingUp,
    /// Writing.
    Writing,
    /// Reading back what was written.
    Verifying,
}

/// What a failed upload left on the device.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Left<I> {
    /// Nothing was written: the device holds what it held.
    Untouched,
    /// Writing had begun: these items reached the device (the first may have
    /// erased it), of `total`.
    Partly {
        /// The items acknowledged, in order.
        reached: Vec<I>,
        /// Items the upload had to write.
        total: usize,
    },
    /// Everything was written; what failed came after.
    Everything,
}

/// An upload that failed, with where it stopped and what it left.
#[derive(Debug)]
pub struct UploadFailure<E, I> {
    /// What went wrong.
    pub error: E,
    /// What was running.
    pub stage: Stage,
    /// What the device holds now.
    pub left: Left<I>,
    /// Where the device's previous contents were saved, if they were.
    pub backup: Option<PathBuf>,
}

impl<E, I> UploadFailure<E, I> {
    /// A failure before anything was written.
    pub fn untouched(error: E, stage: Stage, backup: Option<PathBuf>) -> Self {
        Self { error, stage, left: Left::Untouched, backup }
    }
}

impl<E: fmt::Display, I: fmt::Display> fmt::Display for UploadFailure<E, I> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.stage {
            Stage::BackingUp => write!(f, "while backing the device up: {}", self.error)?,
            Stage::Verifying => write!(f, "while verifying: {}", self.error)?,
            Stage::Checking | Stage::Writing => write!(f, "{}", self.error)?,
        }
        match &self.left {
            Left::Untouched => write!(f, "\nnothing was written: the device holds what it held")?,
            Left::Partly { reached, total } => {
                let names: Vec<String> = reached.iter().take(6).map(ToString::to_string).collect();
                let more = if reached.len() > names.len() { ", …" } else { "" };
                write!(
                    f,
                    "\nthe device may now be half written: {} of {total} items reached it ({}{more})",
                    reached.len(),
                    if names.is_empty() { "none acknowledged".to_string() } else { names.join(", ") }
                )?;
            }
            Left::Everything => write!(f, "\neverything was written")?,
        }
        if let Some(backup) = &self.backup {
            write!(f, "\nthe device's previous contents are saved in {}", backup.display())?;
        }
        Ok(())
    }
}

/// The steps of an upload, each family's own; [`upload`] runs them in order
/// and says, when one fails, what it left on the device.
pub trait UploadSteps {
    /// Why a step failed.
    type Error;
    /// What is written, item by item.
    type Item;
    /// What a finished upload reports.
    type Report;
    /// Everything done before the device is touched: validation, does it
    /// fit, how the link delivers. Nothing is written when it fails.
    fn check(&mut self) -> Result<(), Self::Error>;
    /// Reads what the device holds and saves it, when asked to; where.
    fn back_up(&mut self) -> Result<Option<PathBuf>, Self::Error>;
    /// Writes, pushing onto `reached` each item the device took whole.
    fn write(&mut self, reached: &mut Vec<Self::Item>) -> Result<(), Self::Error>;
    /// How many items the write had to write in all.
    fn total(&self) -> usize;
    /// Reads back what was written and compares, when asked to.
    fn verify(&mut self) -> Result<(), Self::Error>;
    /// The report of the finished upload.
    fn report(self, backup: Option<PathBuf>) -> Self::Report;
}

/// How an upload of `S`'s steps failed.
pub type FailedUpload<S> = Box<UploadFailure<<S as UploadSteps>::Error, <S as UploadSteps>::Item>>;

/// Runs an upload's steps: check, back up, write, verify. A failure is boxed
/// (it is built once per failed upload) and says where it stopped, what it
/// left — nothing, the items that reached the device, or everything — and
/// where the backup is.
pub fn upload<S: UploadSteps>(mut steps: S) -> Result<S::Report, FailedUpload<S>> {
    let untouched = |error, stage| Box::new(UploadFailure::untouched(error, stage, None));
    steps.check().map_err(|error| untouched(error, Stage::Checking))?;
    let backup = steps.back_up().map_err(|error| untouched(error, Stage::BackingUp))?;
    let mut reached = Vec::new();
    if let Err(error) = steps.write(&mut reached) {
        let left = Left::Partly { reached, total: steps.total() };
        return Err(Box::new(UploadFailure { error, stage: Stage::Writing, left, backup }));
    }
    if let Err(error) = steps.verify() {
        return Err(Box::new(UploadFailure { error, stage: Stage::Verifying, left: Left::Everything, backup }));
    }
    Ok(steps.report(backup))
}

impl<E: std::error::Error + 'static, I: fmt::Debug + fmt::Display> std::error::Error for UploadFailure<E, I> {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cancel_once_asked_stays_asked_in_every_clone() {
        let (trigger, cancel) = Cancel::new();
        let other = cancel.clone();
        assert!(!cancel.is_requested());
        trigger.send(()).unwrap();
        assert!(cancel.is_requested());
        assert!(cancel.is_requested(), "asked twice");
        assert!(other.is_requested(), "the clone shares it");
        assert!(!Cancel::never().is_requested());
    }

    #[test]
    fn a_failure_says_what_it_left_and_where_the_backup_is() {
        let untouched: UploadFailure<&str, &str> =
            UploadFailure::untouched("action 17: the link was lost", Stage::BackingUp, None);
        let text = untouched.to_string();
        assert!(text.starts_with("while backing the device up: action 17"), "{text}");
        assert!(text.contains("nothing was written"), "{text}");

        let partly = UploadFailure {
            error: "action 3: no response",
            stage: Stage::Writing,
            left: Left::Partly { reached: vec!["clear all", "project id 7"], total: 12 },
            backup: Some(PathBuf::from("/tmp/board-backup.json")),
        };
        let text = partly.to_string();
        assert!(text.contains("half written: 2 of 12 items reached it (clear all, project id 7)"), "{text}");
        assert!(text.contains("saved in /tmp/board-backup.json"), "{text}");
    }
}
