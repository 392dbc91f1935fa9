//! How a command that did not finish says so: advice after an error (how to
//! put a device back), the exit status a signal gives, and the errors of an
//! import or export that failed or was interrupted.

use super::{device, signals};

/// An error with advice after it (how to restore the device), keeping the
/// error's causes for whoever reads the chain.
#[derive(Debug)]
pub struct Advised<E> {
    /// The error.
    pub error: E,
    /// What to do, appended to its text.
    pub advice: String,
}

impl<E: std::fmt::Display> std::fmt::Display for Advised<E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}{}", self.error, self.advice)
    }
}

impl<E: std::error::Error> std::error::Error for Advised<E> {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.error.source()
    }
}

/// After a failed upload that had begun writing, how to put the device back
/// as the backup holds it (or that there is no backup).
pub fn restore_hint<I>(protocol: &str, port: &str, backup: Option<&std::path::Path>, left: &device::Left<I>) -> String {
    if matches!(left, device::Left::Untouched) {
        return String::new();
    }
    match backup {
        Some(backup) => format!(
            "\nto put it back as it was: servo-studio import{protocol} --port {port} --in {} --force --yes",
            backup.display()
        ),
        None => "\nthere is no backup of what it held (--no-backup)".to_string(),
    }
}

/// An exit status other than 1, carried up to `main` (it says nothing itself).
#[derive(Debug, thiserror::Error)]
#[error("")]
pub struct Exit(pub u8);

/// The error for an operation a signal stopped before it finished: `what`
/// it left, and the status a shell gives a command ended by that signal.
pub fn interrupted(interrupt: signals::Interrupt, what: &str) -> anyhow::Error {
    anyhow::Error::new(Exit(interrupt.exit_code)).context(format!("interrupted by {interrupt}: {what}"))
}

/// The error of an import that failed, or that `interrupt` stopped at its
/// safe point (then the status is the signal's), with `advice` after it.
pub fn import_failed<E: std::error::Error + Send + Sync + 'static>(
    failure: E,
    advice: String,
    interrupt: Option<signals::Interrupt>,
    input: &std::path::Path,
    port: &str,
) -> anyhow::Error {
    let failed = anyhow::Error::new(Advised { error: failure, advice });
    match interrupt {
        Some(interrupt) => failed
            .context(format!("import of {} into {port} was interrupted by {interrupt}", input.display()))
            .context(Exit(interrupt.exit_code)),
        None => failed.context(format!("import of {} into {port} failed", input.display())),
    }
}

/// An export's result: stopped by `interrupt` (the signal's status), failed
/// (why), or what was read; when it did not finish, `out` was not written.
pub fn exported<T, E: std::error::Error + Send + Sync + 'static>(
    result: Result<T, E>,
    interrupt: Option<signals::Interrupt>,
    port: &str,
    out: &std::path::Path,
) -> anyhow::Result<T> {
    if let (Err(_), Some(interrupt)) = (&result, interrupt) {
        return Err(interrupted(interrupt, &format!("export from {port}: {} was not written", out.display())));
    }
    result.map_err(|error| {
        anyhow::Error::new(error).context(format!("export from {port} failed; {} was not written", out.display()))
    })
}
