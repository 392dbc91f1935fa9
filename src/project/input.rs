//! Reading what a user names as input — a project file, a PLEN2 motion.json,
//! or a folder of them — without ever blocking or running out of memory: only
//! regular files are read (a named pipe or a device is refused at once, by
//! name), up to a size cap; a folder's entries that cannot be read are
//! reported with the reason, never skipped in silence.

use std::path::{Path, PathBuf};

use super::document::Project;
use super::family::Family;
use super::file::{LoadError, Loaded, parse};
use super::motion_json::{self, MotionJsonError};
use super::plen2::Plen2Project;
pub use super::read::{
    MAX_MOTION_BYTES, MAX_PROJECT_BYTES, ReadError, not_a_file, open_regular, read_bytes, read_text,
};

/// "Too many levels of symbolic links".
#[cfg(target_os = "linux")]
const ELOOP: i32 = 40;
#[cfg(not(target_os = "linux"))]
const ELOOP: i32 = 62;

/// An entry of a folder that is not read, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Skipped {
    /// The entry.
    pub path: PathBuf,
    /// Why, in words.
    pub why: String,
    /// Whether it was meant to be read (a `*.json` entry): then it is an error.
    pub is_error: bool,
}

impl std::fmt::Display for Skipped {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let name =
            self.path.file_name().map_or_else(|| self.path.display().to_string(), |n| n.to_string_lossy().into());
        write!(f, "{name}: {}", self.why)
    }
}

/// A folder's `*.json` files, in file-name order, and every other entry with
/// why it is not read: a `*.json` that is a dangling link, a loop of links, a
/// named pipe or unreadable is an error; anything else is a note.
pub fn folder_entries(folder: &Path) -> Result<(Vec<PathBuf>, Vec<Skipped>), ReadError> {
    let io = |source| ReadError::Io { path: folder.to_path_buf(), source };
    let mut files = Vec::new();
    let mut skipped = Vec::new();
    for entry in std::fs::read_dir(folder).map_err(io)? {
        let path = entry.map_err(io)?.path();
        let is_json = path.extension().is_some_and(|ext| ext.eq_ignore_ascii_case("json"));
        let why = match std::fs::metadata(&path) {
            Ok(metadata) => match not_a_file(&metadata.file_type()) {
                None if is_json => {
                    files.push(path);
                    continue;
                }
                None => "not a .json file".to_string(),
                Some(what) => format!("{what}, not a file"),
            },
            Err(error) if error.raw_os_error() == Some(ELOOP) => "a loop of symbolic links".to_string(),
            Err(error) if error.kind() == std::io::ErrorKind::NotFound => {
                "a symbolic link to nothing (dangling)".to_string()
            }
            Err(error) => format!("cannot be read: {error}"),
        };
        skipped.push(Skipped { path, why, is_error: is_json });
    }
    files.sort();
    skipped.sort_by(|a, b| a.path.cmp(&b.path));
    Ok((files, skipped))
}

/// What an opened input was.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputKind {
    /// A Servo Studio project file: saving writes back to it.
    ProjectFile,
    /// One motion.json, or a folder of them: a new, unsaved PLEN2 project.
    Motions,
}

/// An input opened as a project.
#[derive(Clone, Debug, PartialEq)]
pub struct Opened {
    /// The project and its unknown keys.
    pub loaded: Loaded,
    /// What the input was.
    pub kind: InputKind,
}

/// An input could not be opened.
#[derive(Debug, thiserror::Error)]
pub enum OpenError {
    /// The file could not be read.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// A project file that cannot be read as one.
    #[error("cannot read {path}: {source}")]
    Project {
        /// The file.
        path: PathBuf,
        /// Why.
        source: LoadError,
    },
    /// A motion.json (or a folder of them) that cannot be read.
    #[error(transparent)]
    Motion(#[from] MotionJsonError),
    /// A folder's entry that cannot be read: the folder is not opened in part.
    #[error("{folder}: {skipped}")]
    Entry {
        /// The folder.
        folder: PathBuf,
        /// The entry and why.
        skipped: Skipped,
    },
}

/// Opens what a user names: a project file, one motion.json, or a folder of
/// motion.json files (read in file-name order), each read only when it is a
/// regular file within the size cap.
pub fn open(path: &Path) -> Result<Opened, OpenError> {
    let motions = |motions, unknown_keys: Vec<String>| Opened {
        loaded: Loaded {
            project: Project {
                family: Family::Plen2,
                plen2: Plen2Project { motions, ..Default::default() },
                ..Project::default()
            },
            unknown_keys,
            unknown_keys_not_kept: 0,
        },
        kind: InputKind::Motions,
    };
    if path.is_dir() {
        let (files, skipped) = folder_entries(path)?;
        if let Some(skipped) = skipped.into_iter().find(|skipped| skipped.is_error) {
            return Err(OpenError::Entry { folder: path.to_path_buf(), skipped });
        }
        if files.is_empty() {
            return Err(MotionJsonError::Empty { path: path.to_path_buf() }.into());
        }
        let mut all = Vec::new();
        let mut unknown_keys = Vec::new();
        for file in files {
            let (motion, unknown) = motion_json::read_motion_file(&file)?;
            let name = file.file_name().map_or_else(String::new, |name| name.to_string_lossy().into_owned());
            unknown_keys.extend(unknown.into_iter().map(|key| format!("{name}: {key}")));
            all.push(motion);
        }
        return Ok(motions(all, unknown_keys));
    }
    let text = read_text(path, MAX_PROJECT_BYTES)?;
    if motion_json::looks_like_motion(&text) {
        if u64::try_from(text.len()).unwrap_or(u64::MAX) > MAX_MOTION_BYTES {
            let bytes = u64::try_from(text.len()).unwrap_or(u64::MAX);
            return Err(ReadError::TooLarge { path: path.to_path_buf(), bytes, max: MAX_MOTION_BYTES }.into());
        }
        let (motion, unknown) = motion_json::read_motion(&text)
            .map_err(|reason| MotionJsonError::NotAMotion { path: path.to_path_buf(), reason })?;
        return Ok(motions(vec![motion], unknown));
    }
    // The text is dropped before the document is checked: a large file is not held twice.
    let parsed = parse(&text);
    drop(text);
    let loaded = parsed.map_err(|source| OpenError::Project { path: path.to_path_buf(), source })?;
    Ok(Opened { loaded, kind: InputKind::ProjectFile })
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    #[test]
    fn a_fifo_a_device_and_a_folder_are_refused_by_name_without_opening_them() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("pipe.json");
        assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
        // Opening a FIFO for reading would block until a writer came: refused before.
        let error = read_text(&fifo, MAX_PROJECT_BYTES).unwrap_err();
        assert_eq!(error.to_string(), format!("{} is a named pipe (FIFO), not a file: it is not read", fifo.display()));
        let error = read_text(Path::new("/dev/zero"), MAX_PROJECT_BYTES).unwrap_err();
        assert!(matches!(error, ReadError::NotAFile { what: "a device", .. }), "{error}");
        let error = read_text(dir.path(), MAX_PROJECT_BYTES).unwrap_err();
        assert!(matches!(error, ReadError::NotAFile { what: "a folder", .. }), "{error}");
    }

    #[test]
    fn a_file_over_the_cap_and_a_file_that_is_not_text_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let big = dir.path().join("big.json");
        std::fs::write(&big, vec![b' '; 2000]).unwrap();
        assert!(matches!(read_text(&big, 1000), Err(ReadError::TooLarge { bytes: 2000, max: 1000, .. })));
        assert_eq!(read_text(&big, 2000).unwrap().len(), 2000);
        let binary = dir.path().join("image.json");
        std::fs::write(&binary, b"{\"a\": \xff\xfe}").unwrap();
        assert!(matches!(read_text(&binary, 1000), Err(ReadError::NotText { valid_up_to: 6, .. })));
    }

    #[test]
    fn a_folder_says_why_each_entry_it_does_not_read_is_left() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path();
        std::fs::write(folder.join("a.json"), "{}").unwrap();
        std::fs::write(folder.join("notes.txt"), "").unwrap();
        std::os::unix::fs::symlink("missing.json", folder.join("dangling.json")).unwrap();
        std::os::unix::fs::symlink("loop2.json", folder.join("loop1.json")).unwrap();
        std::os::unix::fs::symlink("loop1.json", folder.join("loop2.json")).unwrap();
        assert!(std::process::Command::new("mkfifo").arg(folder.join("pipe.json")).status().unwrap().success());
        let (files, skipped) = folder_entries(folder).unwrap();
        assert_eq!(files, [folder.join("a.json")]);
        let said: Vec<(String, bool)> = skipped.iter().map(|s| (s.to_string(), s.is_error)).collect();
        assert_eq!(
            said,
            [
                ("dangling.json: a symbolic link to nothing (dangling)".to_string(), true),
                ("loop1.json: a loop of symbolic links".to_string(), true),
                ("loop2.json: a loop of symbolic links".to_string(), true),
                ("notes.txt: not a .json file".to_string(), false),
                ("pipe.json: a named pipe (FIFO), not a file".to_string(), true),
            ]
        );
        let error = open(folder).unwrap_err();
        assert_eq!(
            error.to_string(),
            format!("{}: dangling.json: a symbolic link to nothing (dangling)", folder.display())
        );
    }
}
