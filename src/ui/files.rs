//! Keeping work safe: the recovery file written by autosave, and the list of
//! recent files.

use std::path::{Path, PathBuf};
use std::time::Duration;

use serde::{Deserialize, Serialize};

use crate::project::{Project, atomic_write, from_json, to_json};

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

/// Writes the recovery file atomically.
pub fn write_recovery(data_dir: &Path, path: Option<&Path>, project: &Project) -> std::io::Result<()> {
    std::fs::create_dir_all(data_dir)?;
    let recovery = RecoveryFile {
        path: path.map(Path::to_path_buf),
        saved_at: chrono::Local::now().format("%Y-%m-%d %H:%M:%S").to_string(),
        project: serde_json::from_str(&to_json(project)).map_err(std::io::Error::other)?,
    };
    let text = serde_json::to_string_pretty(&recovery).map_err(std::io::Error::other)?;
    atomic_write(&recovery_path(data_dir), |file| std::io::Write::write_all(file, text.as_bytes()))
}

/// The recovery file left by a session that did not end cleanly, if any.
pub fn read_recovery(data_dir: &Path) -> Option<Recovery> {
    let text = std::fs::read_to_string(recovery_path(data_dir)).ok()?;
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
        write_recovery(dir.path(), Some(Path::new("/tmp/robot.json")), &project).unwrap();
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
