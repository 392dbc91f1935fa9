//! The PLEN2's operations in words: why one failed, what the robot panel
//! says after one — in the interface's language.

use crate::device::plen2::{Plen2Item, Plen2OpError, ReplyError, SlotResult};
use crate::ui::i18n::{Language, Worded};

use super::{Plen2Failure, Plen2Result};
use crate::ui::plen2::captions::Plen2Words;

impl Plen2Failure {
    /// Why a PLEN2 operation failed, in `language`.
    pub fn words(&self, language: Language) -> String {
        match self {
            Self::Op(error) => error.worded(language),
            Self::Upload(failure) => {
                language.upload_failure(failure, |error| error.worded(language), |item| item.worded(language))
            }
            Self::Reply(error) => error.worded(language),
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
                (Plen2OpError::Invalid { problems: problems.clone() }.worded(language), true)
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

/// What a PLEN2 operation step works on, in this language.
impl Worded for Plen2Item {
    fn worded(&self, language: Language) -> String {
        let item = self;
        if language == Language::English {
            return item.to_string();
        }
        match item {
            Plen2Item::Version => "韌體版本".into(),
            Plen2Item::JointSettings => "關節設定".into(),
            Plen2Item::Joint(joint) => format!("關節 {}", joint.name()),
            Plen2Item::Slot { slot, name } if name.is_empty() => format!("槽位 {slot}"),
            Plen2Item::Slot { slot, name } => format!("槽位 {slot} {name:?}"),
            Plen2Item::Link => "連線".into(),
            Plen2Item::Erased { slot, remaining } => {
                let mut text = format!(
                    "槽位 {slot} 從未寫入：機器人會先送出整個未寫入的記憶體（約 300 KB），之後才讀取下一個指令"
                );
                if let Some(left) = remaining {
                    text.push_str(&format!("；在這條連線上約還需 {} 秒", left.as_secs().max(1)));
                }
                text
            }
            Plen2Item::Pacing => "傳送節奏".into(),
            Plen2Item::FactoryReset => "出廠關節設定".into(),
            Plen2Item::Done => "完成".into(),
        }
    }
}

/// Why a PLEN2 did not answer, in this language, with what to try.
impl Worded for ReplyError {
    fn worded(&self, language: Language) -> String {
        let error = self;
        match (language, error) {
            (Language::English, _) => error.to_string(),
            (_, ReplyError::Timeout { timeout_ms }) => {
                format!("{timeout_ms} 毫秒內沒有回應。機器人是否已開機、鮑率 2,000,000、DTR 已啟用？")
            }
            (_, ReplyError::NotThisProtocol { bytes }) => {
                format!("裝置有回應（{bytes} 位元組），但不是 PLEN2 的協定。它是 PLEN2 嗎？")
            }
            (_, ReplyError::Garbage { bytes }) => format!("回應是 {bytes} 位元組的無效資料"),
            (_, ReplyError::Disconnected) => "與機器人的連線已中斷".into(),
            (_, ReplyError::Stopped) => "傳送前已按下停止：沒有傳送".into(),
        }
    }
}

/// Why a PLEN2 operation step failed, in this language.
impl Worded for Plen2OpError {
    fn worded(&self, language: Language) -> String {
        let error = self;
        if language == Language::English {
            return error.to_string();
        }
        match error {
            Plen2OpError::Reply { item, source } => format!("{}：{}", item.worded(language), source.worded(language)),
            Plen2OpError::Unreadable { item } => {
                format!("{}：裝置有回應，但不是 PLEN2 的協定。它是韌體 1.4.x 的 PLEN2 嗎？", item.worded(language))
            }
            Plen2OpError::Invalid { problems } => {
                let list = language.problem_lines(problems);
                format!("專案有 {} 個錯誤，沒有寫入任何資料：\n{}", problems.errors(), list.join("\n"))
            }
            Plen2OpError::Backup(error) => format!("備份失敗，因此沒有寫入任何資料：{}", language.save_error(error)),
            Plen2OpError::Unstorable(error) => {
                use crate::device::plen2::NotStorable;
                let why = match error.why {
                    NotStorable::Frames(count) => format!("它有 {count} 個影格，PLEN2 的動作只能有 1 到 20 個"),
                    NotStorable::Slot => "PLEN2 只有 0 到 89 號槽位".to_string(),
                    NotStorable::Name => "名稱最多 20 個可列印的 ASCII 字元".to_string(),
                };
                format!("動作 {} {:?} 無法存進 PLEN2，沒有寫入任何資料：{why}", error.slot, error.name)
            }
            Plen2OpError::Cancelled => "已取消".into(),
        }
    }
}

// A PLEN2 says its version; it reads the same in every language.
inventory::submit! {
    crate::ui::i18n::SaidWords(|identity, _| identity.said::<crate::device::plen2::Said>().map(ToString::to_string))
}
