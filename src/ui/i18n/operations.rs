//! Device operations in words: what a step works on, why it failed and what
//! an upload left, in the interface's language. Operations report typed
//! outcomes; they become words here and in each family's ui (its own
//! failures and results).

use crate::device::plen2::{Plen2Item, Plen2OpError, ReplyError};
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

    /// What a PLEN2 operation step works on, in this language.
    pub fn plen2_item(self, item: &Plen2Item) -> String {
        if self == Self::English {
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

    /// Why a PLEN2 did not answer, in this language, with what to try.
    pub fn reply_error(self, error: &ReplyError) -> String {
        match (self, error) {
            (Self::English, _) => error.to_string(),
            (_, ReplyError::Timeout { timeout_ms }) => {
                format!("{timeout_ms} 毫秒內沒有回應。機器人是否已開機、鮑率 2,000,000、DTR 已啟用？")
            }
            (_, ReplyError::NotThisProtocol { bytes }) => {
                format!("裝置有回應（{bytes} 位元組），但不是 PLEN2 的協定。它是 PLEN2 嗎？")
            }
            (_, ReplyError::Garbage { bytes }) => format!("回應是 {bytes} 位元組的無效資料"),
            (_, ReplyError::Disconnected) => "與機器人的連線已中斷".into(),
        }
    }

    /// Why a PLEN2 operation step failed, in this language.
    pub fn plen2_op_error(self, error: &Plen2OpError) -> String {
        if self == Self::English {
            return error.to_string();
        }
        match error {
            Plen2OpError::Reply { item, source } => format!("{}：{}", self.plen2_item(item), self.reply_error(source)),
            Plen2OpError::Unreadable { item } => {
                format!("{}：裝置有回應，但不是 PLEN2 的協定。它是韌體 1.4.x 的 PLEN2 嗎？", self.plen2_item(item))
            }
            Plen2OpError::Invalid { problems } => {
                let mut list: Vec<String> = problems
                    .iter()
                    .take(20)
                    .map(|p| format!("{}：{}", self.location(&p.location), self.problem(&p.kind)))
                    .collect();
                let more = problems.errors() + problems.warnings() - list.len();
                if more > 0 {
                    list.push(format!("……還有 {more} 個（servo-studio check 會全部列出）"));
                }
                format!("專案有 {} 個錯誤，沒有寫入任何資料：\n{}", problems.errors(), list.join("\n"))
            }
            Plen2OpError::Backup(error) => format!("備份失敗，因此沒有寫入任何資料：{}", self.save_error(error)),
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
