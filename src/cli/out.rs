//! Standard output for the command line: a reader that goes away (`| head -1`)
//! ends the command quietly instead of panicking, and nothing more is printed.

use std::io::Write;

/// Stdout was closed by its reader: the command ends quietly with status 0.
#[derive(Debug, thiserror::Error)]
#[error("standard output was closed")]
pub struct Closed;

/// Prints one line on standard output.
pub fn line(text: &str) -> Result<(), Closed> {
    let mut stdout = std::io::stdout().lock();
    // Any write error is the reader gone (a closed pipe) or nowhere to write: nobody reads on.
    writeln!(stdout, "{text}").and_then(|()| stdout.flush()).map_err(|_| Closed)
}
