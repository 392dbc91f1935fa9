//! Reading a file a user names as text, without ever blocking or running out
//! of memory: only regular files are read (a named pipe or a device is
//! refused at once, by name), up to a size cap.

use std::io::Read;
use std::path::{Path, PathBuf};

/// The largest project file read, bytes (a board's whole memory is a few
/// hundred kilobytes; the biggest real projects are a few megabytes).
pub const MAX_PROJECT_BYTES: u64 = 256 * 1024 * 1024;
/// The largest motion.json read, bytes (a 20-frame motion is about 20 KB).
pub const MAX_MOTION_BYTES: u64 = 16 * 1024 * 1024;

/// A file could not be read as text.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The file could not be opened or read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// What the path names is not a regular file; it was not opened (a named
    /// pipe would block until something writes to it, a device never ends).
    #[error("{path} is {what}, not a file: it is not read")]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it is: "a named pipe (FIFO)", "a device", "a folder"…
        what: &'static str,
    },
    /// The file is larger than any file of its kind.
    #[error("{path} is {} MB; a file over {} MB is not read (is it the right file?)", .bytes / 1_000_000, .max / 1_000_000)]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size.
        bytes: u64,
        /// The largest read.
        max: u64,
    },
    /// The bytes are not UTF-8 text.
    #[error("{path} is not text (not UTF-8 from byte {valid_up_to}): is it a project or motion.json file?")]
    NotText {
        /// The file.
        path: PathBuf,
        /// How many bytes were valid text.
        valid_up_to: usize,
    },
}

/// What a file system entry is, in words, when it is not a regular file.
pub fn not_a_file(kind: &std::fs::FileType) -> Option<&'static str> {
    if kind.is_file() {
        return None;
    }
    if kind.is_dir() {
        return Some("a folder");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return Some("a named pipe (FIFO)");
        }
        if kind.is_char_device() || kind.is_block_device() {
            return Some("a device");
        }
        if kind.is_socket() {
            return Some("a socket");
        }
    }
    Some("not a regular file")
}

/// Opens the regular file `path` (symbolic links followed) for reading,
/// refusing anything else — a named pipe, a device, a socket, a folder, or a
/// link to one — before reading a byte, and any file over `max_bytes`.
/// Checked twice: by its name before it is opened, and again on what was
/// opened (a pipe put in its place meanwhile is opened without waiting for a
/// writer, and refused). Returns the file and its size.
pub fn open_regular(path: &Path, max_bytes: u64) -> Result<(std::fs::File, u64), ReadError> {
    let io = |source| ReadError::Io { path: path.to_path_buf(), source };
    let checked = |metadata: &std::fs::Metadata| {
        if let Some(what) = not_a_file(&metadata.file_type()) {
            return Err(ReadError::NotAFile { path: path.to_path_buf(), what });
        }
        if metadata.len() > max_bytes {
            return Err(ReadError::TooLarge { path: path.to_path_buf(), bytes: metadata.len(), max: max_bytes });
        }
        Ok(metadata.len())
    };
    checked(&std::fs::metadata(path).map_err(io)?)?;
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(O_NONBLOCK);
    }
    let file = options.open(path).map_err(io)?;
    let bytes = checked(&file.metadata().map_err(io)?)?;
    Ok((file, bytes))
}

/// Opening without waiting: a named pipe opens at once instead of blocking
/// until a writer comes (it is then refused); no effect on a regular file.
#[cfg(any(target_os = "linux", target_os = "android"))]
const O_NONBLOCK: i32 = 0o4000;
#[cfg(all(unix, not(any(target_os = "linux", target_os = "android"))))]
const O_NONBLOCK: i32 = 0x0004;

/// The bytes of the regular file `path` (symbolic links followed), refusing
/// anything else before opening it, and any file over `max_bytes`.
pub fn read_bytes(path: &Path, max_bytes: u64) -> Result<Vec<u8>, ReadError> {
    let io = |source| ReadError::Io { path: path.to_path_buf(), source };
    let too_large = |bytes| ReadError::TooLarge { path: path.to_path_buf(), bytes, max: max_bytes };
    let (file, length) = open_regular(path, max_bytes)?;
    let mut bytes = Vec::with_capacity(usize::try_from(length).unwrap_or(0));
    // A file that grows while it is read stops at the cap all the same.
    file.take(max_bytes.saturating_add(1)).read_to_end(&mut bytes).map_err(io)?;
    if u64::try_from(bytes.len()).unwrap_or(u64::MAX) > max_bytes {
        return Err(too_large(u64::try_from(bytes.len()).unwrap_or(u64::MAX)));
    }
    Ok(bytes)
}

/// The text of the regular file `path`, as [`read_bytes`] reads it, when it is UTF-8.
pub fn read_text(path: &Path, max_bytes: u64) -> Result<String, ReadError> {
    String::from_utf8(read_bytes(path, max_bytes)?)
        .map_err(|error| ReadError::NotText { path: path.to_path_buf(), valid_up_to: error.utf8_error().valid_up_to() })
}
