//! Keeping work safe: the recovery file written by autosave, the list of
//! recent files, and the file work the window never waits for — every
//! open, save, autosave and export runs in order on one worker thread
//! ([`FileWork`]) and reports back on a channel.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use crossbeam_channel::{Receiver, Sender};
use serde::{Deserialize, Serialize};

use crate::link::Waker;
use crate::project::{Project, SaveError, atomic_write, from_json, to_json};

/// Writes a whole file (atomically: the old content stays whole until the new
/// one is). Tests give one that blocks, to prove the window does not wait.
pub type FileWriter = Arc<dyn Fn(&Path, &[u8]) -> std::io::Result<()> + Send + Sync>;

/// The system's writer: a temporary file beside the target, then a rename.
pub fn system_writer() -> FileWriter {
    Arc::new(|path: &Path, bytes: &[u8]| atomic_write(path, |file| std::io::Write::write_all(file, bytes)))
}

type Job = Box<dyn FnOnce() + Send>;

/// File work off the window's thread: jobs run one after the other (a save
/// and the autosave after it never overtake each other), each answer comes
/// back on its own channel and wakes the window.
#[derive(Clone)]
pub struct FileWork {
    jobs: Option<Sender<Job>>,
    writer: FileWriter,
    waker: Waker,
}

impl std::fmt::Debug for FileWork {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FileWork").field("running", &self.jobs.is_some()).finish_non_exhaustive()
    }
}

impl FileWork {
    /// Starts the worker thread; files are written with `writer`.
    pub fn start(writer: FileWriter, waker: Waker) -> Self {
        let (jobs, queue) = crossbeam_channel::unbounded::<Job>();
        let spawned = std::thread::Builder::new().name("files".into()).spawn(move || {
            for job in queue {
                job();
            }
        });
        // No thread: the work is done where it is asked for (slow, but nothing is lost).
        Self { jobs: spawned.is_ok().then_some(jobs), writer, waker }
    }

    /// Runs `job` on the worker; its answer arrives on the receiver.
    pub fn run<T: Send + 'static>(&self, job: impl FnOnce(&FileWriter) -> T + Send + 'static) -> Receiver<T> {
        let (answer, answered) = crossbeam_channel::bounded(1);
        let (writer, waker) = (self.writer.clone(), self.waker.clone());
        let work = move || {
            let _ = answer.send(job(&writer));
            waker();
        };
        match &self.jobs {
            Some(jobs) => {
                if let Err(crossbeam_channel::SendError(work)) = jobs.send(Box::new(work)) {
                    work();
                }
            }
            None => work(),
        }
        answered
    }

    /// Writes `bytes` to `path` on the worker.
    pub fn write(&self, path: PathBuf, bytes: Vec<u8>) -> Receiver<Result<(), SaveError>> {
        self.run(move |writer| writer(&path, &bytes).map_err(|source| SaveError::new(&path, source)))
    }

    /// Saves `project` to `path` on the worker (the JSON is made here, from the project as it is now).
    pub fn save(&self, path: PathBuf, project: &Project) -> Receiver<Result<(), SaveError>> {
        self.write(path, to_json(project).into_bytes())
    }
}

/// How often unsaved changes are written to the recovery file.
pub const AUTOSAVE_EVERY: Duration = Duration::from_secs(30);
/// How many recent files are remembered.
pub const MAX_RECENT: usize = 8;

/// What autosave keeps: the unsaved project and the file it belongs to.
#[derive(Clone, Debug, PartialEq)]
pub struct Recovery {
    /// The file the project was opened from or saved to, if any.
    pub path: Option<PathBuf>,
    /// When it was written (local time, for the offer's wording).
    pub saved_at: String,
    /// The unsaved project.
    pub project: Project,
}

/// The recovery file: the project is kept as a project file, so that it
/// migrates like one.
#[derive(Serialize, Deserialize)]
struct RecoveryFile {
    path: Option<PathBuf>,
    saved_at: String,
    project: serde_json::Value,
}

/// The recovery file inside a data folder.
pub fn recovery_path(data_dir: &Path) -> PathBuf {
    data_dir.join("recovery.json")
}

/// The recovery file's bytes for `project` (opened from or saved to `path`).
pub fn recovery_bytes(path: Option<&Path>, project: &Project) -> std::io::Result<Vec<u8>> {
    let recovery = RecoveryFile {
        path: path.map(Path::to_path_buf),
        saved_at: chrono::Local::now().format("%Y-%m-%d %H:%M:%S").to_string(),
        project: serde_json::from_str(&to_json(project)).map_err(std::io::Error::other)?,
    };
    Ok(serde_json::to_string_pretty(&recovery).map_err(std::io::Error::other)?.into_bytes())
}

/// Writes the recovery file with `writer`.
pub fn write_recovery_with(writer: &FileWriter, data_dir: &Path, bytes: &[u8]) -> std::io::Result<()> {
    std::fs::create_dir_all(data_dir)?;
    writer(&recovery_path(data_dir), bytes)
}

/// The recovery file left by a session that did not end cleanly, if any:
/// read only when it is a regular file within a project file's size cap.
pub fn read_recovery(data_dir: &Path) -> Option<Recovery> {
    let text =
        crate::project::input::read_text(&recovery_path(data_dir), crate::project::input::MAX_PROJECT_BYTES).ok()?;
    let file: RecoveryFile = serde_json::from_str(&text).ok()?;
    let project = from_json(&file.project.to_string()).ok()?;
    Some(Recovery { path: file.path, saved_at: file.saved_at, project })
}

/// Removes the recovery file (after a save, or when the user declines it).
pub fn clear_recovery(data_dir: &Path) {
    // Absent already is fine.
    let _ = std::fs::remove_file(recovery_path(data_dir));
}

/// Puts `path` first in `recent`, without duplicates, keeping at most [`MAX_RECENT`].
pub fn remember(recent: &mut Vec<PathBuf>, path: &Path) {
    recent.retain(|known| known != path);
    recent.insert(0, path.to_path_buf());
    recent.truncate(MAX_RECENT);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovery_round_trips_and_clears() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(read_recovery(dir.path()), None);
        let project = Project::servo(crate::project::ServoProject { project_id: 3, ..Default::default() });
        let bytes = recovery_bytes(Some(Path::new("/tmp/robot.json")), &project).unwrap();
        write_recovery_with(&system_writer(), dir.path(), &bytes).unwrap();
        let recovered = read_recovery(dir.path()).unwrap();
        assert_eq!(recovered.project, project);
        assert_eq!(recovered.path.as_deref(), Some(Path::new("/tmp/robot.json")));
        clear_recovery(dir.path());
        assert_eq!(read_recovery(dir.path()), None);
    }

    #[test]
    fn recent_files_are_unique_newest_first_and_bounded() {
        let mut recent = Vec::new();
        for index in 0..10 {
            remember(&mut recent, Path::new(&format!("/p/{index}.json")));
        }
        remember(&mut recent, Path::new("/p/5.json"));
        assert_eq!(recent.len(), MAX_RECENT);
        assert_eq!(recent[0], PathBuf::from("/p/5.json"));
        assert_eq!(recent[1], PathBuf::from("/p/9.json"));
        assert_eq!(recent.iter().filter(|p| **p == Path::new("/p/5.json")).count(), 1);
    }
}
