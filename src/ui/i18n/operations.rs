//! Device operations in words: what a step works on, why it failed and what
//! an upload left, in the interface's language. Operations report typed
//! outcomes; they become words here and in each family's ui (its own
//! failures and results).

use crate::device::{Left, Stage, UploadFailure};

use super::Language;
use crate::say;

impl Language {
    /// A failed upload of any family: why (`error` words it), and what it
    /// left on the device (`item` words each item), in this language.
    pub fn upload_failure<E: std::fmt::Display, I: std::fmt::Display>(
        self,
        failure: &UploadFailure<E, I>,
        error: impl Fn(&E) -> String,
        item: impl Fn(&I) -> String,
    ) -> String {
        if self == Self::English {
            return failure.to_string();
        }
        let reason = error(&failure.error);
        let mut text = match failure.stage {
            Stage::BackingUp => say!(self, "upload.backing_up", reason),
            Stage::Verifying => say!(self, "upload.verifying", reason),
            Stage::Checking | Stage::Writing => reason,
        };
        match &failure.left {
            Left::Untouched => text.push_str(&format!("\n{}", say!(self, "upload.untouched"))),
            Left::Partly { reached, total } => {
                let names: Vec<String> = reached.iter().take(6).map(&item).collect();
                let (count, names) = (reached.len(), names.join(self.word("file.list_comma")));
                text.push_str(&format!("\n{}", say!(self, "upload.partly", total, count, names)));
            }
            Left::Everything => text.push_str(&format!("\n{}", say!(self, "upload.everything"))),
        }
        if let Some(backup) = &failure.backup {
            text.push_str(&format!("\n{}", say!(self, "upload.backed_up", backup = backup.display())));
        }
        text
    }

    /// No thread could be started for an operation.
    pub fn no_worker(self, error: &std::io::Error) -> String {
        say!(self, "upload.no_worker", error)
    }
}
