//! Standard output and error for the command line. Output that cannot be
//! written is an error, never a silent success: a reader that went away
//! (`| head -1`) ends the command with 141, as a shell reports a command
//! killed by SIGPIPE, unless the command's result was already decided; any
//! other failure (a full disk) is said on stderr. Messages on stderr never
//! panic, wherever stderr goes.

use std::io::Write;

/// Standard output could not be written.
#[derive(Debug, thiserror::Error)]
pub enum Unwritten {
    /// Its reader closed the pipe.
    #[error("standard output was closed")]
    Closed,
    /// Writing failed otherwise (a full disk, a device error).
    #[error("cannot write the output: {0}")]
    Failed(std::io::Error),
}

impl Unwritten {
    /// The exit status for output that could not be written: 141 for a
    /// closed pipe (128 + SIGPIPE), 1 for any other failure.
    pub fn exit_code(&self) -> u8 {
        match self {
            Self::Closed => 141,
            Self::Failed(_) => 1,
        }
    }
}

/// Prints one line on standard output.
pub fn line(text: &str) -> Result<(), Unwritten> {
    if closed_at_start() {
        return Err(Unwritten::Failed(std::io::Error::other(
            "standard output is closed (`>&-`): what was to be printed would go nowhere; send it to a file or a pipe",
        )));
    }
    let mut stdout = std::io::stdout().lock();
    writeln!(stdout, "{text}").and_then(|()| stdout.flush()).map_err(|error| match error.kind() {
        std::io::ErrorKind::BrokenPipe => Unwritten::Closed,
        _ => Unwritten::Failed(error),
    })
}

/// Whether standard output was closed when the command started (`>&-`). The
/// Rust runtime then opens `/dev/null` in its place, for reading and writing,
/// so that every write "succeeds" into nothing; a shell's `> /dev/null` (or a
/// parent's null device for output) opens it for writing only. Read once from
/// `/proc` (Linux); elsewhere a closed stdout is not told apart.
fn closed_at_start() -> bool {
    static CLOSED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *CLOSED.get_or_init(|| {
        let null =
            std::fs::read_link("/proc/self/fd/1").is_ok_and(|target| target == std::path::Path::new("/dev/null"));
        null && std::fs::read_to_string("/proc/self/fdinfo/1").is_ok_and(|info| read_write(&info))
    })
}

/// Whether an fdinfo text's `flags:` (octal) open the file for reading and writing (`O_RDWR`).
fn read_write(fdinfo: &str) -> bool {
    fdinfo
        .lines()
        .find_map(|line| line.strip_prefix("flags:"))
        .and_then(|flags| u32::from_str_radix(flags.trim(), 8).ok())
        .is_some_and(|flags| flags & 0o3 == 0o2)
}

/// Writes a message on standard error. Nothing is done when stderr cannot be
/// written (closed, a full disk): a message must never end a command.
pub fn say_line(message: std::fmt::Arguments<'_>) {
    // Clippy keeps `eprintln!` (which panics when stderr fails) out of the crate; this is its replacement.
    let _ = writeln!(std::io::stderr(), "{message}");
}

/// Like [`say_line`], without the line end (a progress line redrawn in place).
pub fn say_partial(message: std::fmt::Arguments<'_>) {
    let mut stderr = std::io::stderr();
    let _ = write!(stderr, "{message}").and_then(|()| stderr.flush());
}

/// `say!("…", args)`: a line on stderr that never panics.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::cli::out::say_line(format_args!($($arg)*))
    };
}
pub(crate) use say;

#[cfg(test)]
mod tests {
    #[test]
    fn the_access_mode_is_read_from_fdinfo() {
        assert!(super::read_write("pos:\t0\nflags:\t0100002\nmnt_id:\t27\n"), "O_RDWR | O_LARGEFILE");
        assert!(!super::read_write("pos:\t0\nflags:\t0100001\n"), "O_WRONLY");
        assert!(!super::read_write("flags:\t02000000\n"), "O_RDONLY");
        assert!(!super::read_write("pos:\t0\n"), "no flags line");
    }
}
