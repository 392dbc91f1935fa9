//! What the window never waits for: the serial-port list (read on its own
//! thread every two seconds), files (opened, saved and autosaved on the file
//! worker), and a closing link (a base's shutdown waits for its brake). Each
//! reports back on a channel; the frame only looks at what has arrived.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use crossbeam_channel::{Receiver, RecvTimeoutError, Sender};

use super::*;
use crate::link::{LinkError, list_ports};
use crate::project::SaveError;
use crate::project::input::{OpenError, Opened, ReadError};

/// Reads the list of serial ports. Tests give one that blocks, to prove the
/// window does not wait for a stuck driver.
pub type PortLister = Arc<dyn Fn() -> Result<Vec<PortInfo>, LinkError> + Send + Sync>;

/// The system's port list.
pub fn system_lister() -> PortLister {
    Arc::new(list_ports)
}

/// How often the port list is read again.
const RESCAN_EVERY: Duration = Duration::from_secs(2);

/// The port list, read on its own thread.
#[derive(Debug)]
pub(super) struct PortScanner {
    lists: Receiver<Vec<PortInfo>>,
    /// Dropped with the scanner: the thread ends at its next turn.
    _stop: Sender<()>,
}

impl PortScanner {
    fn start(lister: PortLister, waker: Waker) -> Option<Self> {
        let (lists_tx, lists) = crossbeam_channel::bounded(1);
        let (stop, stopped) = crossbeam_channel::bounded::<()>(0);
        std::thread::Builder::new()
            .name("port list".into())
            .spawn(move || {
                loop {
                    // A failed scan leaves the last list; the port can still be typed.
                    // A list the window has not taken yet is newer than none: this one waits for the next turn.
                    if let Ok(ports) = lister()
                        && lists_tx.try_send(ports).is_ok()
                    {
                        waker();
                    }
                    match stopped.recv_timeout(RESCAN_EVERY) {
                        Err(RecvTimeoutError::Timeout) => {}
                        _ => break,
                    }
                }
            })
            .ok()?;
        Some(Self { lists, _stop: stop })
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

impl StudioApp {
    /// Reads ports with `lister` instead of the system's (tests give one that blocks).
    pub fn with_port_lister(mut self, lister: PortLister) -> Self {
        self.lister = lister;
        self.scanner = None;
        self
    }

    /// Writes files with `writer` instead of the system's (tests give one that blocks).
    pub fn with_file_writer(mut self, writer: files::FileWriter) -> Self {
        self.files = files::FileWork::start(writer, self.waker.clone());
        self
    }

    /// Takes the newest port list, starting the scanner the first time.
    pub(super) fn scan_ports(&mut self) {
        if self.scanner.is_none() {
            self.scanner = PortScanner::start(self.lister.clone(), self.waker.clone());
        }
        if let Some(ports) = self.scanner.as_ref().and_then(|scanner| scanner.lists.try_iter().last()) {
            self.ports = ports;
        }
    }

    /// Saves the project to `path` off the frame; `then` goes on once it is saved.
    pub(super) fn save_to(&mut self, path: PathBuf, then: Option<AfterUnsaved>) {
        let done = self.files.save(path.clone(), &self.document.project);
        self.report(format!("{} {}", self.words().msg_saving, path.display()), false);
        self.file_jobs.push(FileJob::Saving { path, revision: self.document.revision(), then, done });
    }

    /// Whether the project is being saved.
    pub fn saving(&self) -> bool {
        self.file_jobs.iter().any(|job| matches!(job, FileJob::Saving { .. }))
    }

    /// Has what waits on the unsaved-changes question go on after the save
    /// already running (Save as… then continue), if one runs.
    pub(super) fn continue_after_save(&mut self, next: AfterUnsaved) -> Result<(), AfterUnsaved> {
        match self.file_jobs.iter_mut().rev().find(|job| matches!(job, FileJob::Saving { .. })) {
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
        let done = self.files.run(move |_| crate::project::input::open(&reading));
        self.file_jobs.push(FileJob::Opening { path, done });
    }

    /// Writes the recovery file off the frame (one at a time).
    pub(super) fn autosave_later(&mut self) {
        if self.file_jobs.iter().any(|job| matches!(job, FileJob::Autosaving { .. })) {
            return;
        }
        let bytes = match files::recovery_bytes(self.document.path.as_deref(), &self.document.project) {
            Ok(bytes) => bytes,
            Err(error) => return self.report(self.language.autosave_failed(&error), true),
        };
        let data_dir = self.data_dir.clone();
        let done = self.files.run(move |writer| files::write_recovery_with(writer, &data_dir, &bytes));
        self.file_jobs.push(FileJob::Autosaving { done });
    }

    /// Reads the recovery file off the frame: the offer appears when it is read.
    pub(super) fn read_recovery_later(&mut self) {
        let data_dir = self.data_dir.clone();
        let reading = data_dir.clone();
        let done = self.files.run(move |_| files::read_recovery(&reading));
        self.file_jobs.push(FileJob::Recovering { data_dir, done });
    }

    /// Removes the recovery file, after whatever file work was asked before.
    pub(super) fn clear_recovery_later(&mut self) {
        let data_dir = self.data_dir.clone();
        let done = self.files.run(move |_| files::clear_recovery(&data_dir));
        self.file_jobs.push(FileJob::Clearing { done });
    }

    /// Takes the answers of finished file work, waiting up to `wait` for
    /// all of it (None: not at all — the frame never waits).
    pub fn finish_file_work(&mut self, wait: Option<Duration>) {
        let deadline = wait.map(|wait| Instant::now() + wait);
        loop {
            for job in std::mem::take(&mut self.file_jobs) {
                let left = deadline.map(|deadline| deadline.saturating_duration_since(Instant::now()));
                self.take_answer(job, left);
            }
            // What the answers started (a save clears the recovery file) is waited for too.
            if self.file_jobs.is_empty() || deadline.is_none_or(|deadline| Instant::now() >= deadline) {
                break;
            }
        }
    }

    fn take_answer(&mut self, job: FileJob, left: Option<Duration>) {
        match job {
            FileJob::Saving { path, revision, then, done } => {
                match answer(&done, left, || Err(SaveError::new(&path, worker_gone()))) {
                    Some(result) => self.saved(path, revision, result, then),
                    None => self.file_jobs.push(FileJob::Saving { path, revision, then, done }),
                }
            }
            FileJob::Opening { path, done } => match answer(&done, left, || {
                Err(OpenError::Read(ReadError::Io { path: path.clone(), source: worker_gone() }))
            }) {
                Some(result) => self.opened(path, result),
                None => self.file_jobs.push(FileJob::Opening { path, done }),
            },
            FileJob::Autosaving { done } => match answer(&done, left, || Err(worker_gone())) {
                Some(Ok(())) => {}
                Some(Err(error)) => self.report(self.language.autosave_failed(&error), true),
                None => self.file_jobs.push(FileJob::Autosaving { done }),
            },
            FileJob::Clearing { done } => {
                if answer(&done, left, || ()).is_none() {
                    self.file_jobs.push(FileJob::Clearing { done });
                }
            }
            FileJob::Recovering { data_dir, done } => match answer(&done, left, || None) {
                // An offer read from a folder the editor no longer uses is not made.
                Some(offer) if data_dir == self.data_dir => self.recovery_offer = offer,
                Some(_) => {}
                None => self.file_jobs.push(FileJob::Recovering { data_dir, done }),
            },
        }
    }

    fn saved(&mut self, path: PathBuf, revision: u64, result: Result<(), SaveError>, then: Option<AfterUnsaved>) {
        match result {
            Ok(()) => {
                files::remember(&mut self.recent, &path);
                self.clear_recovery_later();
                self.report(format!("{} {}", self.words().msg_saved, path.display()), false);
                self.document.path = Some(path);
                // Edits made while the file was written are still unsaved.
                if self.document.revision() == revision {
                    self.document.dirty = false;
                }
                if let Some(next) = then {
                    self.unsaved_prompt = None;
                    self.after_unsaved(next);
                }
            }
            Err(error) => self.report(self.language.save_error(&error), true),
        }
    }

    /// Closes the link without waiting for it: a base's shutdown (stop, then
    /// brake) finishes on its own thread; the window's end waits for it.
    pub(super) fn close_link(&mut self) {
        let Some(link) = self.link.take() else { return };
        // No thread: the link is shut down here, as the closure is dropped.
        if let Ok(closing) = std::thread::Builder::new().name("link shutdown".into()).spawn(move || drop(link)) {
            self.closing.push(closing);
        }
        self.closing.retain(|closing| !closing.is_finished());
    }

    /// Waits for every link being closed (the window is going: the base must have stopped).
    pub(super) fn wait_for_closing_links(&mut self) {
        for closing in self.closing.drain(..) {
            let _ = closing.join();
        }
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
