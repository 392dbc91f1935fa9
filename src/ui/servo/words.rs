//! The servo board's errors in words, in the interface's language: worded
//! here, beside the family that meets them, through [`Worded`].

use crate::ui::i18n::{Language, Worded};

/// What an operation step is about, in this language.
impl Worded for crate::device::servo::Item {
    fn worded(&self, language: Language) -> String {
        let item = self;
        use crate::device::servo::Item as I;
        if language == Language::English {
            return item.to_string();
        }
        match item {
            I::ProjectId => "專案編號".into(),
            I::ServoParameters => "舵機參數".into(),
            I::ActionList => "動作清單".into(),
            I::Action { id, caption } => format!("動作 {id} {caption:?}"),
            I::MacroList => "巨集清單".into(),
            I::Macro { id, caption } => format!("巨集 {id} {caption:?}"),
            I::TableList => "遙控對應表清單".into(),
            I::Table { id, caption } => format!("遙控對應表 {id} {caption:?}"),
            I::ActiveTable => "使用中的遙控對應表".into(),
            I::MemorySize => "記憶體容量".into(),
            I::ClearAll => "清除所有資料".into(),
            I::WriteProjectId(id) => format!("專案編號 {id}"),
            I::AddServoParameters(count) => format!("{count} 個舵機參數"),
            I::SetActiveTable(id) => format!("使用中的遙控對應表 {id}"),
            I::MoveServos => "移動舵機".into(),
            I::RunAction(id) => format!("執行動作 {id}"),
            I::RunMacro(id) => format!("執行巨集 {id}"),
            I::ServoSwitches(id) => format!("舵機 {id} 開關"),
            I::AngleUnit(id) => format!("舵機 {id} 角度單位"),
            I::ServoState(id) => format!("舵機 {id} 狀態"),
            I::Battery => "電量".into(),
            I::ButtonEvents => "按鍵事件".into(),
        }
    }
}

/// A difference between project and board, in this language.
impl Worded for crate::device::servo::Difference {
    fn worded(&self, language: Language) -> String {
        let difference = self;
        use crate::device::servo::{Difference as D, RecordKind as K};
        if language == Language::English {
            return difference.to_string();
        }
        let kind = |kind: &K| match kind {
            K::Servo => "舵機",
            K::Action => "動作",
            K::Macro => "巨集",
            K::Table => "遙控對應表",
        };
        match difference {
            D::ProjectId { expected, actual } => format!("專案編號：應為 {expected}，控制板為 {actual}"),
            D::Missing { kind: k, id } => format!("{} {id}：控制板上沒有", kind(k)),
            D::Differs { kind: k, id } => format!("{} {id}：控制板上的內容不同", kind(k)),
            D::Extra { kind: k, id } => format!("{} {id}：控制板上有，專案中沒有", kind(k)),
            D::Order { kind: k } => format!("{}：儲存順序不同", kind(k)),
            D::ActiveTable { expected, actual } => format!("使用中的對應表：應為 {expected}，控制板為 {actual}"),
        }
    }
}

/// Why a request failed, in this language, with what to try.
impl Worded for crate::device::servo::RequestError {
    fn worded(&self, language: Language) -> String {
        let error = self;
        use crate::device::servo::RequestError as R;
        match (language, error) {
            (Language::English, _) => error.to_string(),
            (_, R::Timeout { request, attempts, timeout_ms }) => {
                format!(
                    "{request}：嘗試 {attempts} 次，每次等候 {timeout_ms} 毫秒都沒有回應。請確認控制板已開機、鮑率相符、線材已接好"
                )
            }
            (_, R::Incomplete { request, received, expected, timeout_ms, .. }) => {
                format!(
                    "{request}：回應已開始，但表頭之後 {timeout_ms} 毫秒內沒有收完（{received}／{expected} 位元組）。線路太慢或遺失資料：請確認鮑率與線材"
                )
            }
            (_, R::NotThisProtocol { request, bytes }) => {
                format!("{request}：裝置有回應（{bytes} 位元組），但不是這個協定。它是伺服控制板嗎？請確認板子種類")
            }
            (_, R::Malformed { request, .. }) => {
                format!("{request}：回應格式錯誤（封包紀錄中有詳細內容）。請確認鮑率與控制板型號")
            }
            (_, R::Encode(_)) => "無法編碼此訊息：內容超出協定欄位的範圍".to_string(),
            (_, R::Disconnected { .. }) => "與控制板的連線已中斷".to_string(),
            (_, R::Stopped { request }) => format!("{request}：傳送前已按下停止：沒有傳送"),
        }
    }
}

/// Why a board operation failed, in this language, with what to try.
impl Worded for crate::device::servo::OpError {
    fn worded(&self, language: Language) -> String {
        let error = self;
        use crate::device::servo::OpError as O;
        if language == Language::English {
            return error.to_string();
        }
        match error {
            O::Request { item, source } => format!("{}：{}", item.worded(language), source.worded(language)),
            O::Refused { item } => {
                format!("{}：控制板拒絕了（result 0）。記憶體是否已滿，或項目格式有誤？", item.worded(language))
            }
            O::ReadFailed { item } => format!("{}：控制板回報讀取失敗", item.worded(language)),
            O::Invalid { problems } => {
                let list = language.problem_lines(problems);
                format!(
                    "專案有 {} 個錯誤，沒有寫入任何資料：\n{}\n請修正，或用「仍要上傳」（命令列 `import --force`）照原樣還原",
                    problems.errors(),
                    list.join("\n")
                )
            }
            O::DoesNotFit { needed_bytes, total_bytes } => {
                format!(
                    "專案需要 {needed_bytes} 位元組，但控制板只有 {total_bytes}；沒有寫入任何資料。請移除一些動作或巨集"
                )
            }
            O::Image(crate::device::servo::ImageError::CaptionTooLong { item, bytes }) => {
                format!("{item}：標題有 {bytes} 個 UTF-8 位元組；控制板最多儲存 32 個。請縮短它")
            }
            O::Encode(error) => format!("無法編碼：{error}"),
            O::Backup(error) => format!("備份失敗，因此沒有寫入任何資料：{error}"),
            O::Verify { differences } => {
                let list: Vec<String> = differences.iter().map(|d| d.worded(language)).collect();
                format!("驗證失敗：控制板與專案不同：\n{}", list.join("\n"))
            }
            O::Cancelled => "已取消".into(),
            O::Unexpected { item, response } => format!("{}：非預期的回應 {response}", item.worded(language)),
        }
    }
}

/// Why a run time cannot be computed.
impl Worded for crate::project::TimingError {
    fn worded(&self, language: Language) -> String {
        let error = self;
        use crate::project::TimingError as T;
        match (language, error) {
            (Language::English, _) => error.to_string(),
            (_, T::MissingAction(id)) => format!("動作 {id} 不存在"),
            (_, T::MissingMacro(id)) => format!("巨集 {id} 不存在"),
            (_, T::Cycle(id)) => format!("巨集 {id} 會呼叫到自己，永遠不會結束"),
            (_, T::ZeroRatio) => "速度比例 0 % 永遠不會結束".to_string(),
        }
    }
}

/// Why a message cannot be put into a frame (too many entries, too long).
impl Worded for crate::device::servo::EncodeError {
    fn worded(&self, language: Language) -> String {
        let error = self;
        use crate::device::servo::EncodeError as E;
        match (language, error) {
            (Language::English, _) => error.to_string(),
            (_, E::TooMany { message, field, max, actual }) => {
                format!("{message} 的 `{field}` 最多 {max} 筆，但有 {actual} 筆")
            }
            (_, E::ContentTooLong { packet_id, max_bytes, actual_bytes }) => {
                format!("封包 {packet_id}：內容有 {actual_bytes} 位元組，一個封包最多 {max_bytes} 位元組")
            }
        }
    }
}

/// Something could not be sent.
pub(crate) fn send_failed(language: Language, error: &crate::device::servo::EncodeError) -> String {
    match language {
        Language::English => format!("could not send: {error}"),
        Language::TraditionalChinese => format!("無法傳送：{}", error.worded(language)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A message that cannot be encoded used to reach the Chinese interface in
    /// English; a lost link is one phrase.
    #[test]
    fn send_and_request_errors_keep_their_detail_in_chinese() {
        let zh = Language::TraditionalChinese;
        let error = crate::device::servo::EncodeError::TooMany {
            message: "ExecuteActionRequest",
            field: "servoCount",
            max: 255,
            actual: 300,
        };
        assert_eq!(send_failed(zh, &error), "無法傳送：ExecuteActionRequest 的 `servoCount` 最多 255 筆，但有 300 筆");
        assert!(send_failed(Language::English, &error).contains("at most 255 entries, but 300"));
        let lost = crate::device::servo::RequestError::Disconnected { reason: "the link is closed".into() };
        assert_eq!(lost.worded(zh), "與控制板的連線已中斷");
    }
}

/// What a servo board said of itself, in this language.
impl Worded for crate::device::servo::Said {
    fn worded(&self, language: Language) -> String {
        if language == Language::English {
            return self.to_string();
        }
        let mut text = "伺服控制板".to_string();
        match self.project_id {
            Some(0) => text.push_str("，沒有專案"),
            Some(id) => text.push_str(&format!("，專案 {id}")),
            None => {}
        }
        match self.memory {
            Some((free, Some(total))) => text.push_str(&format!("，{total} 位元組中 {free} 可用")),
            Some((free, None)) => text.push_str(&format!("，{free} 位元組可用")),
            None => {}
        }
        text
    }
}

inventory::submit! {
    crate::ui::i18n::SaidWords(|identity, language| {
        identity.said::<crate::device::servo::Said>().map(|said| said.worded(language))
    })
}
