//! What the window never waits for, seen from the shell: the serial-port
//! list (read on its own thread every two seconds: [`LinkDesk`]), files
//! (opened, saved and autosaved on the file worker: [`FileDesk`]), and a
//! closing link (a base's shutdown waits for its brake). Each reports back on
//! a channel; the frame only looks at what has arrived, and acts on it here.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use super::file_desk::FileAnswer;
use super::*;
use crate::link::{LinkError, list_ports};
use crate::project::SaveError;

/// Reads the list of serial ports. Tests give one that blocks, to prove the
/// window does not wait for a stuck driver.
pub type PortLister = Arc<dyn Fn() -> Result<Vec<PortInfo>, LinkError> + Send + Sync>;

/// The system's port list.
pub fn system_lister() -> PortLister {
    Arc::new(list_ports)
}

impl StudioApp {
    #[cfg(any(test, feature = "test-api"))]
    /// Reads ports with `lister` instead of the system's (tests give one that blocks).
    pub fn with_port_lister(mut self, lister: PortLister) -> Self {
        self.links.list_with(lister);
        self
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Writes files with `writer` instead of the system's (tests give one that blocks).
    pub fn with_file_writer(mut self, writer: files::FileWriter) -> Self {
        self.files.work = files::FileWork::start(writer, self.window.waker.clone());
        self
    }

    /// Saves the project to `path` off the frame; `then` goes on once it is saved.
    pub(super) fn save_to(&mut self, path: PathBuf, then: Option<AfterUnsaved>) {
        self.say(|language| format!("{} {}", language.strings().msg_saving, path.display()), false);
        self.files.save(path, &self.document.project, self.document.revision(), then);
    }

    /// Whether the project is being saved.
    pub fn saving(&self) -> bool {
        self.files.saving()
    }

    /// Writes the recovery file off the frame (one at a time).
    pub(super) fn autosave_later(&mut self) {
        if let Err(error) = self.files.autosave_later(self.document.path.as_deref(), &self.document.project) {
            self.say(|language| language.autosave_failed(&error), true);
        }
    }

    /// Takes the answers of finished file work, waiting up to `wait` for
    /// all of it (None: not at all — the frame never waits).
    pub fn finish_file_work(&mut self, wait: Option<Duration>) {
        let deadline = wait.map(|wait| Instant::now() + wait);
        loop {
            for answer in self.files.poll(deadline) {
                self.file_answer(answer);
            }
            // What the answers started (a save clears the recovery file) is waited for too.
            if self.files.idle() || deadline.is_none_or(|deadline| Instant::now() >= deadline) {
                break;
            }
        }
    }

    fn file_answer(&mut self, answer: FileAnswer) {
        match answer {
            FileAnswer::Saved { path, revision, result, then } => self.saved(path, revision, result, then),
            FileAnswer::Opened { path, result } => self.opened(path, result),
            FileAnswer::AutosaveFailed(error) => self.say(|language| language.autosave_failed(&error), true),
        }
    }

    fn saved(&mut self, path: PathBuf, revision: u64, result: Result<(), SaveError>, then: Option<AfterUnsaved>) {
        match result {
            Ok(()) => {
                files::remember(&mut self.files.recent, &path);
                self.files.clear_recovery_later();
                self.say(|language| format!("{} {}", language.strings().msg_saved, path.display()), false);
                self.document.path = Some(path);
                // Edits made while the file was written are still unsaved.
                if self.document.revision() == revision {
                    self.document.dirty = false;
                }
                if let Some(next) = then {
                    self.files.unsaved_prompt = None;
                    self.after_unsaved(next);
                }
            }
            Err(error) => self.say(|language| language.save_error(&error), true),
        }
    }

    /// Closes the link without waiting for it: a base's shutdown (stop, then
    /// brake) finishes on its own thread; the window's end waits for it.
    pub(super) fn close_link(&mut self) {
        if let Some(link) = self.link.take() {
            self.links.close(link);
        }
    }
}
