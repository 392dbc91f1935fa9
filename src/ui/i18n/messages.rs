//! Whole sentences in each language: link and request errors, validation
//! problems, operation errors, status lines.

use super::Language;

impl Language {
    /// A link error in this language, with what to try.
    pub fn link_error(self, error: &crate::link::LinkError) -> String {
        use crate::link::LinkError as E;
        match (self, error) {
            (Self::English, _) => error.to_string(),
            (Self::TraditionalChinese, E::BadPortName { name, .. }) => {
                format!("無法辨識連接埠名稱 {name:?}：請輸入序列埠（例如 /dev/ttyUSB0 或 COM3）或 tcp://主機:埠號")
            }
            (Self::TraditionalChinese, E::NotFound { port }) => {
                format!("{port}：找不到此連接埠。控制板是否已插上？`servo-studio ports` 會列出電腦看到的連接埠")
            }
            (Self::TraditionalChinese, E::PermissionDenied { port }) => format!(
                "{port}：沒有權限。在 Linux 上請把自己加入 `dialout` 群組（sudo usermod -aG dialout $USER）後重新登入"
            ),
            (Self::TraditionalChinese, E::Busy { port }) => {
                format!("{port}：連接埠使用中。請關閉其他使用它的程式（另一個 Servo Studio、序列埠監看程式）後重試")
            }
            (Self::TraditionalChinese, E::TimedOut { port, timeout_ms }) => {
                format!("{port}：{timeout_ms} ms 內沒有回應。位址是否正確？橋接器是否已開機並在同一個網路上？")
            }
            (Self::TraditionalChinese, E::Refused { port }) => {
                format!("{port}：連線被拒。該位址上的橋接程式（或 `servo-studio sim --tcp`）是否正在執行？")
            }
            (Self::TraditionalChinese, E::NotAPort { port, what }) => {
                let what = match *what {
                    "a regular file" => "一般檔案",
                    "a folder" => "資料夾",
                    "a named pipe (FIFO)" => "具名管道（FIFO）",
                    "a socket" => "socket",
                    "a block device" => "區塊裝置",
                    _ => "不是終端機的裝置",
                };
                format!(
                    "{port} 是{what}，不是序列埠：請選擇控制板所在的連接埠（`servo-studio ports` 會列出），或 tcp://主機:埠號"
                )
            }
            (Self::TraditionalChinese, E::Open { port, source }) => format!("{port}：無法開啟：{source}"),
        }
    }

    /// A validation problem in this language.
    pub fn problem(self, kind: &crate::project::ProblemKind) -> String {
        if self == Self::English {
            return kind.to_string();
        }
        Self::board_problem(kind).or_else(|| Self::other_problem(kind)).unwrap_or_else(|| kind.to_string())
    }

    /// A servo board's problem (captions, ids, limits, steps, commands, tables), in Chinese.
    fn board_problem(kind: &crate::project::ProblemKind) -> Option<String> {
        use crate::project::{ItemKind, ProblemKind as P};
        let item = |kind: &ItemKind| match kind {
            ItemKind::Servo => "舵機",
            ItemKind::Action => "動作",
            ItemKind::Macro => "巨集",
            ItemKind::Table => "遙控對應表",
        };
        let text = match kind {
            P::CaptionTooLong { bytes } => format!("標題有 {bytes} 個 UTF-8 位元組；控制板最多儲存 32 個"),
            P::IdNotPositive { kind, id } => {
                format!("{}編號必須大於或等於 1（0 在控制板上表示「無」），目前為 {id}", item(kind))
            }
            P::DuplicateId { kind, id } => format!("{}編號 {id} 重複", item(kind)),
            P::ReservedServoId => "舵機編號 255 保留給「所有舵機」；請使用 0..=254".to_string(),
            P::MinAboveMax { min_deg, max_deg } => format!("最小值 {min_deg}° 大於最大值 {max_deg}°"),
            P::HomeOutsideLimits { home_deg, min_deg, max_deg } => {
                format!("原點 {home_deg}° 超出範圍 {min_deg}°..{max_deg}°")
            }
            P::NoSteps => "沒有步驟：執行它不會有動作".to_string(),
            P::ServoTwiceInAction { servo_id } => format!("舵機 {servo_id} 在此動作中已有步驟"),
            P::NegativeInterval { interval_10ms } => format!("時間 {interval_10ms} × 10 ms 為負值"),
            P::MissingServo { servo_id } => format!("舵機 {servo_id} 不存在"),
            P::StepOutsideLimits { degree, servo_id, min_deg, max_deg } => {
                format!("{degree}° 超出舵機 {servo_id} 的範圍 {min_deg}°..{max_deg}°")
            }
            P::NoCommands => "沒有指令：執行它不會有動作".to_string(),
            P::TooManyCommands { count, max } => format!("有 {count} 個指令；一個封包最多容納 {max} 個"),
            P::RatioOutOfRange { ratio_percent } => format!("速度比例 {ratio_percent} % 不在 1..=100 之間"),
            P::LoopBelowOne { loop_count } => format!("重複次數 {loop_count} 必須至少為 1"),
            P::MissingAction { action_id } => format!("動作 {action_id} 不存在"),
            P::MissingMacro { macro_id } => format!("巨集 {macro_id} 不存在"),
            P::NegativeDelay { delay_ms } => format!("延遲 {delay_ms} ms 為負值"),
            P::TotalTooLong { total_ms } => format!("執行 {total_ms} ms，超過控制板能計算的長度（{} ms）", i32::MAX),
            P::MacroCycle { path } => {
                let names: Vec<String> = path.iter().map(ToString::to_string).collect();
                format!("巨集循環 {}：巨集不可呼叫到自己", names.join(" → "))
            }
            _ => return None,
        };
        Some(text)
    }

    /// A rig's, a gamepad binding's, a PLEN2's or any section's problem, in Chinese.
    fn other_problem(kind: &crate::project::ProblemKind) -> Option<String> {
        use crate::project::{ButtonSlot, ProblemKind as P};
        let text = match kind {
            P::RigUnknownParent { parent } => {
                format!("骨架中它裝在舵機 {parent} 上，但該舵機不在骨架中：請為該舵機設定骨架，或改選其他上層")
            }
            P::RigCycle { path } => {
                let names: Vec<String> = path.iter().map(ToString::to_string).collect();
                format!("骨架循環 {}：舵機不可裝在自己身上", names.join(" → "))
            }
            P::RigUnknownTwin { twin } => {
                format!(
                    "左右鏡像的對側是舵機 {twin}，但它不是骨架中的另一個舵機：左右鏡像會保留此步驟；請指定另一側的骨架舵機"
                )
            }
            P::BoundTwice => "重複綁定（或已被其他用途佔用）：只有其中一個綁定有效；請移除其他的".into(),
            P::MissingPlayList { index } => format!("播放清單 {index} 不存在"),
            P::TooManyButtons { count, max } => format!("有 {count} 個按鍵；一個封包最多容納 {max} 個"),
            P::DuplicateButton { button_id } => format!("按鍵編號 0x{button_id:08x} 在此對應表中重複"),
            P::MissingButtonMacro { slot, macro_id } => {
                let event = match slot {
                    ButtonSlot::Press => "按下",
                    ButtonSlot::LongPress => "長按",
                    ButtonSlot::Release => "放開",
                };
                format!("{event}巨集 {macro_id} 不存在")
            }
            P::ButtonRunsNothing => "不會執行任何巨集".to_string(),
            P::MissingActiveTable { table_id } => format!("使用中的遙控對應表 {table_id} 不存在"),
            P::StoredTotalDiffers { stored_ms, derived_ms } => {
                format!("控制板儲存的總時間是 {stored_ms} ms，依專案計算為 {derived_ms} ms；修改此指令之前保留儲存的值")
            }
            P::OutOfRange { field, value, min, max } => format!("{field} {value} 不在 {min}..={max} 之間"),
            P::DuplicateSlot { slot } => format!("位置 {slot} 已有另一個動作"),
            P::DuplicateJoint => "重複列出".to_string(),
            P::NameTooLong { bytes, max } => format!("名稱有 {bytes} 個位元組；機器人最多儲存 {max} 個"),
            P::NameNotAscii => "名稱只能使用可列印的 ASCII 字元（機器人儲存的是位元組）".to_string(),
            P::NoFrames => "沒有任何影格".to_string(),
            P::BadLoopRange { begin_frame, end_frame, frames } => {
                format!("從影格 {begin_frame} 到 {end_frame} 的循環不在它的 {frames} 個影格之內")
            }
            P::MissingMotion { slot } => format!("位置 {slot} 沒有動作"),
            P::LoopRunsForever => {
                "循環次數 0 會永遠循環：機器人會把它倒數成 255（兩遍請填 1，永遠請填 255）".to_string()
            }
            P::JumpBeyondSlots { slot } => {
                format!("跳到位置 {slot}：機器人只有位置 0..=89，因此會永遠重播這個動作")
            }
            P::FirstFrameZeroCycles { transition_ms } => format!(
                "transition_ms {transition_ms} 是 0 個 32 毫秒週期：作為第一個影格，機器人會除以零（行為無法預測）；請填 32..=8191"
            ),
            P::FrameSkipped { transition_ms } => format!(
                "transition_ms {transition_ms} 是 0 個 32 毫秒週期：機器人會跳過這個影格（不會顯示它的姿勢，下一個影格從它開始）"
            ),
            P::NotPositive { field } => format!("{field} 必須是正數"),
            P::UnknownKey => "不認得的欄位，已略過（是否拼錯？）".to_string(),
            _ => return None,
        };
        Some(text)
    }

    /// A project's problems as lines ("where：what", in this language): the
    /// first twenty, then how many more there are (an upload refused says them).
    pub fn problem_lines(self, problems: &crate::project::Problems) -> Vec<String> {
        let mut list: Vec<String> = problems
            .iter()
            .take(20)
            .map(|p| format!("{}：{}", self.location(&p.location), self.problem(&p.kind)))
            .collect();
        let more = problems.errors() + problems.warnings() - list.len();
        if more > 0 {
            list.push(match self {
                Self::English => format!("… and {more} more (servo-studio check lists them all)"),
                Self::TraditionalChinese => format!("……還有 {more} 個（servo-studio check 會全部列出）"),
            });
        }
        list
    }

    /// Where a problem is, in this language.
    pub fn location(self, location: &crate::project::Location) -> String {
        use crate::project::Location as L;
        if self == Self::English {
            return location.to_string();
        }
        match location {
            L::Project => "專案".into(),
            L::Servo { servo_id, caption } => format!("舵機 {servo_id} {caption:?}"),
            L::Action { action_id, caption } => format!("動作 {action_id} {caption:?}"),
            L::Step { action_id, caption, step } => format!("動作 {action_id} {caption:?}，步驟 {step}"),
            L::Macro { macro_id, caption } => format!("巨集 {macro_id} {caption:?}"),
            L::Command { macro_id, caption, command } => format!("巨集 {macro_id} {caption:?}，指令 {command}"),
            L::Table { table_id, caption } => format!("遙控對應表 {table_id} {caption:?}"),
            L::Button { table_id, table_caption, button_id, caption } => {
                format!("遙控對應表 {table_id} {table_caption:?}，按鍵 0x{button_id:08x} {caption:?}")
            }
            L::Joint { joint } => format!("關節 {joint}"),
            L::Motion { slot, name } => format!("動作 {slot} {name:?}"),
            L::Frame { slot, name, frame } => format!("動作 {slot} {name:?}，影格 {frame}"),
            L::PlayList { index, name } => format!("播放清單 {index} {name:?}"),
            L::Robot => "機器人".into(),
            L::GamepadButton { button } => format!("遊戲手把按鈕 0x{button:03x}"),
            L::GamepadAxis { axis } => format!("遊戲手把搖桿軸 {axis}"),
            L::Key { path } => path.clone(),
        }
    }

    /// A family's name.
    pub fn family(self, family: crate::project::Family) -> &'static str {
        use crate::project::Family as F;
        match (self, family) {
            (Self::English, F::Servo) => "Servo board",
            (Self::TraditionalChinese, F::Servo) => "舵機控制板",
            (_, F::Plen2) => "PLEN2",
            (Self::English, F::Rflex) => "rFLEX base",
            (Self::TraditionalChinese, F::Rflex) => "rFLEX 移動底盤",
            // Any other family by its own name.
            (_, family) => family.name(),
        }
    }

    /// "connecting to PORT…".
    pub fn connecting_to(self, port: &str) -> String {
        match self {
            Self::English => format!("connecting to {port}…"),
            Self::TraditionalChinese => format!("正在連線至 {port}…"),
        }
    }

    /// The user stopped a connection attempt.
    pub fn connect_cancelled(self, port: &str) -> String {
        match self {
            Self::English => format!("stopped connecting to {port}"),
            Self::TraditionalChinese => format!("已取消連線至 {port}"),
        }
    }

    /// Why a link ended, as a phrase.
    pub fn disconnect_reason(self, reason: &crate::link::DisconnectReason) -> String {
        use crate::link::DisconnectReason as D;
        match (self, reason) {
            (Self::English, _) => reason.to_string(),
            (_, D::Closed) => "連線已關閉".into(),
            (_, D::ClosedByDriver) => "驅動程式關閉了連線".into(),
            (_, D::ClosedByPeer) => "另一端關閉了連接埠".into(),
            (_, D::ReadFailed(_)) => "讀取連接埠失敗，線材是否被拔掉，或控制板斷電了".into(),
            (_, D::WriteFailed(_)) => "寫入連接埠失敗，線材是否被拔掉，或控制板斷電了".into(),
            (_, D::ThreadFailed(_)) => "連線的讀取執行緒停止了".into(),
        }
    }

    /// The status line when the link ends: one sentence, the reason once.
    pub fn link_ended(self, reason: &crate::link::DisconnectReason) -> String {
        let why = self.disconnect_reason(reason);
        match self {
            Self::English => {
                format!("The board link ended ({why}). Your project is unchanged; reconnect when ready.")
            }
            Self::TraditionalChinese => format!("與控制板的連線已中斷（{why}）。專案未變更，準備好後請重新連線。"),
        }
    }

    /// The backup folder could not be made, so nothing was written.
    pub fn backup_folder_failed(self, folder: &std::path::Path, error: &std::io::Error) -> String {
        match self {
            Self::English => {
                format!("cannot create the backup folder {}: {error}; nothing was written", folder.display())
            }
            Self::TraditionalChinese => {
                format!("無法建立備份資料夾 {}，因此沒有寫入任何資料。請確認磁碟空間與權限", folder.display())
            }
        }
    }

    /// A file opened, but with keys Servo Studio does not know (ignored).
    /// `keys` are the first unknown keys by name, `count` how many there were.
    pub fn opened_with_unknown_keys(self, path: &std::path::Path, keys: &[String], count: usize) -> String {
        let file = path.display();
        let shown: Vec<&str> = keys.iter().take(3).map(String::as_str).collect();
        let more = if count > shown.len() { ", …" } else { "" };
        match self {
            Self::English => {
                format!("opened {file}; {count} unknown key(s) ignored (misspelt?): {}{more}", shown.join(", "))
            }
            Self::TraditionalChinese => {
                format!("已開啟 {file}；略過 {count} 個不認得的欄位（是否拼錯？）：{}{more}", shown.join("、"))
            }
        }
    }

    /// A file that could not be read at all, in one sentence.
    pub fn read_error(self, error: &crate::project::input::ReadError) -> String {
        use crate::project::input::ReadError as E;
        match (self, error) {
            (Self::English, _) => error.to_string(),
            (_, E::Io { path, source }) => format!("無法開啟 {}：{}", path.display(), io_words(source.kind())),
            (_, E::NotAFile { path, .. }) => {
                format!("無法開啟 {}：它不是一般檔案（具名管道、裝置或資料夾）", path.display())
            }
            (_, E::TooLarge { path, bytes, max }) => format!(
                "無法開啟 {}：檔案有 {} MB，超過上限 {} MB（是正確的檔案嗎？）",
                path.display(),
                bytes / 1_000_000,
                max / 1_000_000
            ),
            (_, E::NotText { path, .. }) => format!("無法開啟 {}：內容不是有效的 UTF-8 文字", path.display()),
        }
    }

    /// A project file that could not be opened, in one sentence.
    pub fn load_error(self, path: &std::path::Path, error: &crate::project::LoadError) -> String {
        use crate::project::LoadError as E;
        let file = path.display();
        match (self, error) {
            (Self::English, E::Read(error)) => error.to_string(),
            (Self::English, _) => format!("cannot open {file}: {error}"),
            (_, E::Read(error)) => self.read_error(error),
            (_, E::Syntax { line, column, .. }) => {
                format!("無法開啟 {file}：第 {line} 行第 {column} 欄不是有效的專案內容")
            }
            (_, E::WrongFormat { .. }) => format!("無法開啟 {file}：這不是 Servo Studio 的專案檔"),
            (_, E::NewerVersion { found, .. }) => {
                format!("無法開啟 {file}：它是較新版本的 Servo Studio 所寫（格式版本 {found}）；請更新 Servo Studio")
            }
        }
    }

    /// What the user asked to open (a project, a motion.json, a folder of
    /// them) that could not be opened, in one sentence with its detail.
    pub fn open_error(self, path: &std::path::Path, error: &crate::project::input::OpenError) -> String {
        use crate::project::input::OpenError as E;
        use crate::project::motion_json::MotionJsonError as M;
        match (self, error) {
            (_, E::Read(error)) => self.read_error(error),
            (_, E::Project { source, .. }) => self.load_error(path, source),
            (Self::English, _) => error.to_string(),
            (_, E::Motion(M::Io { path, source })) => {
                format!("無法讀取 {}：{}", path.display(), io_words(source.kind()))
            }
            (_, E::Motion(M::NotAMotion { path, reason })) => {
                format!("{} 不是 PLEN2 的 motion.json：{reason}", path.display())
            }
            (_, E::Motion(M::Empty { path })) => format!("{} 裡沒有 motion.json（*.json）檔案", path.display()),
            (_, E::Entry { folder, skipped }) => {
                format!("無法開啟資料夾 {}（資料夾不會只開啟一部分）：{skipped}", folder.display())
            }
        }
    }

    /// A project file that could not be saved; the previous file is intact.
    pub fn save_error(self, error: &crate::project::SaveError) -> String {
        match self {
            Self::English => error.to_string(),
            Self::TraditionalChinese => format!(
                "無法儲存 {}：{}；{}",
                error.path.display(),
                io_words(error.source.kind()),
                if error.existed { "原本的檔案沒有改變" } else { "沒有寫入任何東西" }
            ),
        }
    }

    /// The recovery file could not be written.
    pub fn autosave_failed(self, error: &std::io::Error) -> String {
        match self {
            Self::English => format!("autosave failed: {error}"),
            Self::TraditionalChinese => format!("自動儲存失敗：{}", io_words(error.kind())),
        }
    }
}

/// What went wrong with a file, in Traditional Chinese.
fn io_words(kind: std::io::ErrorKind) -> &'static str {
    use std::io::ErrorKind as K;
    match kind {
        K::NotFound => "找不到檔案或資料夾",
        K::PermissionDenied => "沒有權限",
        K::StorageFull => "磁碟已滿",
        K::ReadOnlyFilesystem => "磁碟是唯讀的",
        K::InvalidData => "內容不是有效的 UTF-8 文字",
        _ => "讀寫失敗",
    }
}
