//! Device operations in words: what a step works on, why it failed and what
//! an upload left, in the interface's language. Operations report typed
//! outcomes; they become words here and in each family's ui (its own
//! failures and results).

use crate::device::{Left, Stage, UploadFailure};

use super::Language;

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
            Stage::BackingUp => format!("備份裝置時：{reason}"),
            Stage::Verifying => format!("驗證時：{reason}"),
            Stage::Checking | Stage::Writing => reason,
        };
        match &failure.left {
            Left::Untouched => text.push_str("\n沒有寫入任何資料：裝置保持原狀"),
            Left::Partly { reached, total } => {
                let names: Vec<String> = reached.iter().take(6).map(&item).collect();
                text.push_str(&format!(
                    "\n裝置可能只寫入了一部分：{total} 個項目中有 {} 個已寫入（{}）",
                    reached.len(),
                    names.join("、")
                ));
            }
            Left::Everything => text.push_str("\n所有項目都已寫入"),
        }
        if let Some(backup) = &failure.backup {
            text.push_str(&format!("\n裝置原本的內容已備份於 {}", backup.display()));
        }
        text
    }

    /// No thread could be started for an operation.
    pub fn no_worker(self, error: &std::io::Error) -> String {
        match self {
            Self::English => format!("cannot start the operation: {error}"),
            Self::TraditionalChinese => format!("無法開始此操作（{error}）。請關閉其他程式後再試"),
        }
    }
}
