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
///
/// Into /dev/null, opened for writing or for reading and writing (Python's
/// `subprocess.DEVNULL`, a service manager), that is a success: where the
/// output goes is the user's choice. A standard output closed before the
/// command started (`>&-`) is not told apart from that: the runtime opens
/// /dev/null, read-write, in its place before the program's code runs.
pub fn line(text: &str) -> Result<(), Unwritten> {
    let mut stdout = std::io::stdout().lock();
    writeln!(stdout, "{text}").and_then(|()| stdout.flush()).map_err(|error| match error.kind() {
        std::io::ErrorKind::BrokenPipe => Unwritten::Closed,
        _ => Unwritten::Failed(error),
    })
}

/// Writes bytes on standard output as they are (a generated script), as [`line`] does a line.
pub fn bytes(bytes: &[u8]) -> Result<(), Unwritten> {
    let mut stdout = std::io::stdout().lock();
    stdout.write_all(bytes).and_then(|()| stdout.flush()).map_err(|error| match error.kind() {
        std::io::ErrorKind::BrokenPipe => Unwritten::Closed,
        _ => Unwritten::Failed(error),
    })
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
