//! The PLEN2's operations in words: why one failed, what the robot panel
//! says after one — in the interface's language.

use crate::device::plen2::{Plen2OpError, SlotResult};
use crate::ui::i18n::{Language, Worded};

use super::{Plen2Failure, Plen2Result};
use crate::ui::plen2::captions::Plen2Words;

impl Plen2Failure {
    /// Why a PLEN2 operation failed, in `language`.
    pub fn words(&self, language: Language) -> String {
        match self {
            Self::Op(error) => language.plen2_op_error(error),
            Self::Upload(failure) => language.upload_failure(
                failure,
                |error| language.plen2_op_error(error),
                |item| language.plen2_item(item),
            ),
            Self::Reply(error) => language.reply_error(error),
            Self::BackupFolder { folder, error } => language.backup_folder_failed(folder, error),
            Self::Thread(error) => language.no_worker(error),
        }
    }
}

impl Plen2Result {
    /// What the robot panel says after an operation, in `language`, and whether it is an error.
    pub fn words(&self, language: Language) -> (String, bool) {
        let words = language.strings();
        match self {
            Plen2Result::Read(count) => (format!("{} {count}", words.plen2().robot_read), false),
            Plen2Result::Uploaded(report) => {
                let verified = report.slots.iter().filter(|(_, r)| *r == SlotResult::Verified).count();
                let mut text = format!("{} {verified}/{}", words.uploaded_items, report.slots.len());
                let differing: Vec<String> = report
                    .slots
                    .iter()
                    .filter(|(_, r)| *r == SlotResult::Differs)
                    .map(|(slot, _)| slot.to_string())
                    .collect();
                if !differing.is_empty() {
                    text.push_str(&format!("\n{} {}", words.plen2().slots_differ, differing.join(", ")));
                }
                if let Some(backup) = &report.backup {
                    text.push_str(&format!("\n{} {}", words.backup_at, backup.display()));
                }
                (text, !differing.is_empty())
            }
            Plen2Result::JointsWritten(count) => (format!("{}: {count}", words.plen2().write_joints), false),
            Plen2Result::Invalid(problems) => {
                (language.plen2_op_error(&Plen2OpError::Invalid { problems: problems.clone() }), true)
            }
            Plen2Result::ReadIntoProject => (words.read_done.to_string(), false),
            Plen2Result::Exported(path) => (format!("{} {}", words.saved_board_to, path.display()), false),
            Plen2Result::ExportFailed(text) => (text.clone(), true),
            Plen2Result::Failed(failure) => (failure.words(language), true),
            Plen2Result::Cancelled => (words.cancelled.to_string(), false),
        }
    }
}

/// The PLEN2's adaptive pacing widened its margins, in this language.
impl Worded for crate::device::plen2::Widened {
    fn worded(&self, language: Language) -> String {
        let widened = self;
        use crate::device::plen2::{RING_WINDOW_BYTES, WidenReason};
        if language == Language::English {
            return widened.to_string();
        }
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1000.0;
        let window = ms(widened.window);
        match widened.reason {
            WidenReason::Bursts { gap } => format!(
                "傳送節奏已放寬：連線以最長 {:.1} ms 的間隔成批送達；之後每 {window:.1} ms 最多傳送 {RING_WINDOW_BYTES} 位元組",
                ms(gap)
            ),
            WidenReason::Slow { bytes_per_s } => {
                format!("傳送節奏已放寬：連線每秒只傳送 {bytes_per_s} 位元組；之後依這個速率傳送")
            }
            WidenReason::Late { delay } => format!(
                "傳送節奏已放寬：回應最多晚 {:.1} ms 才送達；之後每 {window:.1} ms 最多傳送 {RING_WINDOW_BYTES} 位元組",
                ms(delay)
            ),
            WidenReason::ReadBackDiffered => {
                format!("傳送節奏已放寬：讀回的位置內容不同；之後每 {window:.1} ms 最多傳送 {RING_WINDOW_BYTES} 位元組")
            }
        }
    }
}

/// A PLEN2 pacing mode's name.
pub(crate) fn pacing_name(language: Language, mode: crate::device::plen2::PacingMode) -> &'static str {
    use crate::device::plen2::PacingMode as P;
    match (language, mode) {
        (Language::English, P::Fast) => "Fast",
        (Language::English, P::Adaptive) => "Adaptive",
        (Language::English, P::Safe) => "Safe (official)",
        (Language::TraditionalChinese, P::Fast) => "快速",
        (Language::TraditionalChinese, P::Adaptive) => "自動調整",
        (Language::TraditionalChinese, P::Safe) => "安全（官方）",
    }
}
