//! The file desk: the document's files apart from the document — opening,
//! saving, autosaving and the recovery file on the file worker, recent files,
//! the unsaved-changes question, and the file dialog open.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

use super::{Picker, system_picker};
use crate::link::Waker;
use crate::project::input::{OpenError, Opened, ReadError};
use crate::project::{Project, SaveError};
use crate::ui::action::{AfterUnsaved, FileRequest};
use crate::ui::file_browser::FileBrowser;
use crate::ui::files::{self, FileWork, Recovery};

/// The document's files, apart from the document.
pub struct FileDesk {
    /// Folder for backups and the recovery file.
    pub data_dir: PathBuf,
    /// Recently opened or saved files, newest first.
    pub recent: Vec<PathBuf>,
    /// What waits on the "unsaved changes" question.
    pub unsaved_prompt: Option<AfterUnsaved>,
    /// Work autosaved by a session that did not end cleanly, offered at start.
    pub recovery_offer: Option<Recovery>,
    /// Opening, saving, autosaving and exporting, off the frame.
    pub(super) work: FileWork,
    pub(super) jobs: Vec<FileJob>,
    /// A file dialog open, and the request it answers.
    pub(super) dialog: Option<(FileRequest, Receiver<Option<PathBuf>>)>,
    pub(super) picker: Picker,
    /// Where no system file dialog can appear, what to install for one: the
    /// editor's own picker is used instead (said once).
    pub(super) no_system_dialog: Option<&'static str>,
    /// The editor's own picker, open, and the request it answers.
    pub(super) browser: Option<(FileRequest, FileBrowser)>,
    pub(super) last_autosave: Instant,
}

impl FileDesk {
    /// Nothing open or offered yet; files in the platform's data folder, written the system's way.
    pub(super) fn new(waker: Waker) -> Self {
        Self {
            data_dir: eframe::storage_dir("Servo Studio").unwrap_or_else(|| std::env::temp_dir().join("servo-studio")),
            recent: Vec::new(),
            unsaved_prompt: None,
            recovery_offer: None,
            work: FileWork::start(files::system_writer(), waker),
            jobs: Vec::new(),
            dialog: None,
            picker: system_picker(),
            no_system_dialog: crate::ui::file_browser::no_system_dialog(),
            browser: None,
            last_autosave: Instant::now(),
        }
    }
}

/// File work the window waits on, by what it is for.
#[derive(Debug)]
pub(super) enum FileJob {
    /// The project being saved to `path`, as it was at `revision`; `then`
    /// goes on once it is saved (the unsaved-changes question).
    Saving { path: PathBuf, revision: u64, then: Option<AfterUnsaved>, done: Receiver<Result<(), SaveError>> },
    /// A file being read and parsed.
    Opening { path: PathBuf, done: Receiver<Result<Opened, OpenError>> },
    /// The recovery file being written.
    Autosaving { done: Receiver<std::io::Result<()>> },
    /// The recovery file being removed.
    Clearing { done: Receiver<()> },
    /// The recovery file of `data_dir` being read (at start, off the frame).
    Recovering { data_dir: PathBuf, done: Receiver<Option<Recovery>> },
}

/// A file job's answer the shell acts on (one at a time, as they come: the size of an opened project costs nothing worth a box).
#[derive(Debug)]
#[allow(clippy::large_enum_variant)]
pub(super) enum FileAnswer {
    /// The project was saved to `path` (or not), as it was at `revision`; `then` goes on once saved.
    Saved { path: PathBuf, revision: u64, result: Result<(), SaveError>, then: Option<AfterUnsaved> },
    /// A file was read and parsed (or not).
    Opened { path: PathBuf, result: Result<Opened, OpenError> },
    /// The recovery file could not be written.
    AutosaveFailed(std::io::Error),
}

impl FileDesk {
    /// Saves `project` (at `revision`) to `path` off the frame; `then` goes on once it is saved.
    pub(super) fn save(&mut self, path: PathBuf, project: &Project, revision: u64, then: Option<AfterUnsaved>) {
        let done = self.work.save(path.clone(), project);
        self.jobs.push(FileJob::Saving { path, revision, then, done });
    }

    /// Whether the project is being saved.
    pub fn saving(&self) -> bool {
        self.jobs.iter().any(|job| matches!(job, FileJob::Saving { .. }))
    }

    /// Has what waits on the unsaved-changes question go on after the save
    /// already running (Save as… then continue), if one runs.
    pub(super) fn continue_after_save(&mut self, next: AfterUnsaved) -> Result<(), AfterUnsaved> {
        match self.jobs.iter_mut().rev().find(|job| matches!(job, FileJob::Saving { .. })) {
            Some(FileJob::Saving { then, .. }) => {
                *then = Some(next);
                Ok(())
            }
            _ => Err(next),
        }
    }

    /// Reads and parses `path` off the frame.
    pub(super) fn open_later(&mut self, path: PathBuf) {
        let reading = path.clone();
        let done = self.work.run(move |_| crate::project::input::open(&reading));
        self.jobs.push(FileJob::Opening { path, done });
    }

    /// Writes the recovery file for `project` (saved at `path`) off the frame,
    /// one at a time; an error if it cannot even be put in words.
    pub(super) fn autosave_later(&mut self, path: Option<&Path>, project: &Project) -> std::io::Result<()> {
        if self.jobs.iter().any(|job| matches!(job, FileJob::Autosaving { .. })) {
            return Ok(());
        }
        let bytes = files::recovery_bytes(path, project)?;
        let data_dir = self.data_dir.clone();
        let done = self.work.run(move |writer| files::write_recovery_with(writer, &data_dir, &bytes));
        self.jobs.push(FileJob::Autosaving { done });
        Ok(())
    }

    /// Reads the recovery file off the frame: the offer appears when it is read.
    pub(super) fn read_recovery_later(&mut self) {
        let data_dir = self.data_dir.clone();
        let reading = data_dir.clone();
        let done = self.work.run(move |_| files::read_recovery(&reading));
        self.jobs.push(FileJob::Recovering { data_dir, done });
    }

    /// Removes the recovery file, after whatever file work was asked before.
    pub(super) fn clear_recovery_later(&mut self) {
        let data_dir = self.data_dir.clone();
        let done = self.work.run(move |_| files::clear_recovery(&data_dir));
        self.jobs.push(FileJob::Clearing { done });
    }

    /// Whether no file work waits for an answer.
    pub(super) fn idle(&self) -> bool {
        self.jobs.is_empty()
    }

    /// Takes the answers of finished file work, waiting until `deadline` for
    /// each (None: not at all — the frame never waits). A recovery file read
    /// becomes the offer here; what the shell acts on is returned.
    pub(super) fn poll(&mut self, deadline: Option<Instant>) -> Vec<FileAnswer> {
        let mut answers = Vec::new();
        for job in std::mem::take(&mut self.jobs) {
            let left = deadline.map(|deadline| deadline.saturating_duration_since(Instant::now()));
            if let Some(answered) = self.take_answer(job, left) {
                answers.push(answered);
            }
        }
        answers
    }

    fn take_answer(&mut self, job: FileJob, left: Option<Duration>) -> Option<FileAnswer> {
        match job {
            FileJob::Saving { path, revision, then, done } => {
                match answer(&done, left, || Err(SaveError::new(&path, worker_gone()))) {
                    Some(result) => return Some(FileAnswer::Saved { path, revision, result, then }),
                    None => self.jobs.push(FileJob::Saving { path, revision, then, done }),
                }
            }
            FileJob::Opening { path, done } => match answer(&done, left, || {
                Err(OpenError::Read(ReadError::Io { path: path.clone(), source: worker_gone() }))
            }) {
                Some(result) => return Some(FileAnswer::Opened { path, result }),
                None => self.jobs.push(FileJob::Opening { path, done }),
            },
            FileJob::Autosaving { done } => match answer(&done, left, || Err(worker_gone())) {
                Some(Ok(())) => {}
                Some(Err(error)) => return Some(FileAnswer::AutosaveFailed(error)),
                None => self.jobs.push(FileJob::Autosaving { done }),
            },
            FileJob::Clearing { done } => {
                if answer(&done, left, || ()).is_none() {
                    self.jobs.push(FileJob::Clearing { done });
                }
            }
            FileJob::Recovering { data_dir, done } => match answer(&done, left, || None) {
                // An offer read from a folder the editor no longer uses is not made.
                Some(offer) if data_dir == self.data_dir => self.recovery_offer = offer,
                Some(_) => {}
                None => self.jobs.push(FileJob::Recovering { data_dir, done }),
            },
        }
        None
    }
}

/// What `done` has answered, waiting up to `left` for it (None: not at all).
/// Work that ended without an answer (its thread died) answers `gone`.
fn answer<T>(done: &Receiver<T>, left: Option<Duration>, gone: impl FnOnce() -> T) -> Option<T> {
    let answered = match left {
        None => done.try_recv().map_err(|error| error.is_disconnected()),
        Some(left) => done.recv_timeout(left).map_err(|error| error.is_disconnected()),
    };
    match answered {
        Ok(answer) => Some(answer),
        Err(true) => Some(gone()),
        Err(false) => None,
    }
}

/// Why file work that ended without an answer failed.
fn worker_gone() -> std::io::Error {
    std::io::Error::other("the file worker stopped before it finished")
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;

    const WAIT: Duration = Duration::from_secs(10);

    fn desk(data_dir: &Path, writer: files::FileWriter) -> FileDesk {
        let mut desk = FileDesk::new(crate::link::no_waker());
        desk.data_dir = data_dir.to_path_buf();
        desk.work = FileWork::start(writer, crate::link::no_waker());
        desk
    }

    fn deadline() -> Option<Instant> {
        Some(Instant::now() + WAIT)
    }

    #[test]
    fn a_save_answers_with_its_path_revision_and_what_goes_on_then() {
        let dir = tempfile::tempdir().unwrap();
        let mut desk = desk(dir.path(), files::system_writer());
        let path = dir.path().join("robot.json");
        desk.save(path.clone(), &Project::default(), 7, Some(AfterUnsaved::Quit));
        assert!(desk.saving());
        let answers = desk.poll(deadline());
        let [FileAnswer::Saved { path: saved, revision: 7, result: Ok(()), then: Some(AfterUnsaved::Quit) }] =
            answers.as_slice()
        else {
            panic!("one save answered: {answers:?}");
        };
        assert_eq!(saved, &path);
        assert!(path.is_file() && !desk.saving() && desk.idle());
    }

    #[test]
    fn the_frame_never_waits_for_a_write_that_does_not_finish() {
        let dir = tempfile::tempdir().unwrap();
        let (release, released) = crossbeam_channel::bounded::<()>(0);
        let writer: files::FileWriter = Arc::new(move |_: &Path, _: &[u8]| {
            let _ = released.recv();
            Ok(())
        });
        let mut desk = desk(dir.path(), writer);
        desk.save(dir.path().join("robot.json"), &Project::default(), 1, None);
        assert!(desk.poll(None).is_empty(), "nothing answered yet");
        assert!(desk.saving(), "still waited on");
        drop(release);
        assert_eq!(desk.poll(deadline()).len(), 1);
    }

    #[test]
    fn a_file_that_is_not_there_answers_an_error_and_a_running_save_takes_what_waits() {
        let dir = tempfile::tempdir().unwrap();
        let mut desk = desk(dir.path(), files::system_writer());
        assert_eq!(desk.continue_after_save(AfterUnsaved::New), Err(AfterUnsaved::New), "no save runs");
        desk.open_later(dir.path().join("missing.json"));
        let answers = desk.poll(deadline());
        assert!(matches!(answers.as_slice(), [FileAnswer::Opened { result: Err(_), .. }]), "{answers:?}");
        desk.save(dir.path().join("a.json"), &Project::default(), 1, None);
        assert_eq!(desk.continue_after_save(AfterUnsaved::New), Ok(()));
        let answers = desk.poll(deadline());
        assert!(matches!(answers.as_slice(), [FileAnswer::Saved { then: Some(AfterUnsaved::New), .. }]));
    }

    #[test]
    fn an_autosave_is_offered_back_and_cleared() {
        let dir = tempfile::tempdir().unwrap();
        let mut desk = desk(dir.path(), files::system_writer());
        desk.autosave_later(None, &Project::default()).unwrap();
        assert!(desk.poll(deadline()).is_empty(), "a written recovery file is no news");
        desk.read_recovery_later();
        assert!(desk.poll(deadline()).is_empty());
        assert!(desk.recovery_offer.is_some(), "the offer is made by the desk itself");
        desk.clear_recovery_later();
        desk.recovery_offer = None;
        desk.read_recovery_later();
        desk.poll(deadline());
        assert!(desk.recovery_offer.is_none() && desk.idle());
    }

    #[test]
    fn an_offer_read_from_a_folder_no_longer_used_is_not_made() {
        let (old, new) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
        let mut desk = desk(old.path(), files::system_writer());
        desk.autosave_later(None, &Project::default()).unwrap();
        desk.poll(deadline());
        desk.read_recovery_later();
        desk.data_dir = new.path().to_path_buf();
        desk.poll(deadline());
        assert!(desk.recovery_offer.is_none());
    }
}
