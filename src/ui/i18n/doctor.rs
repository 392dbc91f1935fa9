//! The connection doctor's sentences (what answered on a port, how its link
//! delivers, a lost link waiting for its device to come back) and the
//! gamepad's (a binding in conflict).

use std::time::Duration;

use super::{Language, Worded};
use crate::device::plen2::LinkReport;
use crate::device::probe::{Identity, ProbeResult};

impl Language {
    /// A port is being asked who is there.
    pub fn probing(self, port: &str) -> String {
        match self {
            Self::English => format!("asking {port} which board it is…"),
            Self::TraditionalChinese => format!("正在詢問 {port} 是哪一種控制板…"),
        }
    }

    /// What the doctor found on `port`.
    pub fn probe_result(self, port: &str, result: &ProbeResult) -> String {
        if self == Self::English {
            return format!("{port}: {}", result.describe(None));
        }
        let text = match &result.found {
            Some(found) => {
                format!("{}，鮑率 {}；連線：{}", found.identity.worded(self), found.baud, link_zh(&found.link))
            }
            None if result.unrecognised > 0 => {
                format!("收到 {} 位元組，但不屬於任何一種控制板的協定：可能是其他裝置，或鮑率不同", result.unrecognised)
            }
            None => "沒有任何回應：裝置是否已通電、線材是否接好？（PLEN2 需要 DTR）".to_string(),
        };
        format!("{port}：{text}")
    }

    /// Hardware = Auto, and nothing on `port` said which board it is.
    pub fn auto_found_nothing(self, port: &str, result: &ProbeResult) -> String {
        match self {
            Self::English => format!("cannot connect automatically: {}", self.probe_result(port, result)),
            Self::TraditionalChinese => format!("無法自動連線：{}", self.probe_result(port, result)),
        }
    }

    /// The link ended on its own (a pulled cable): it is made again when the device comes back.
    pub fn lost_waiting(self, reason: &crate::link::DisconnectReason, port: &str) -> String {
        let why = self.disconnect_reason(reason);
        match self {
            Self::English => format!(
                "The board link ended ({why}). Reconnecting by itself when {port} comes back; your project is unchanged."
            ),
            Self::TraditionalChinese => {
                format!("與控制板的連線已中斷（{why}）。{port} 重新出現時會自動重新連線；專案未變更。")
            }
        }
    }

    /// The lost link was made again.
    pub fn reconnected(self, port: &str) -> String {
        match self {
            Self::English => format!("reconnected to {port}: the same device came back"),
            Self::TraditionalChinese => format!("已重新連線至 {port}：同一個裝置回來了"),
        }
    }

    /// Another device appeared where the lost one was: it is not connected to by itself.
    pub fn other_device(self, port: &str, description: &str) -> String {
        match self {
            Self::English => format!(
                "{port} is back, but as a different device ({description}): not reconnecting by itself; connect if it is the board"
            ),
            Self::TraditionalChinese => {
                format!("{port} 回來了，但是另一個裝置（{description}）：不會自動重新連線；若它是控制板請手動連線")
            }
        }
    }
}

/// Why gamepad bindings cannot all work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PadConflict<'a> {
    /// A button bound more than once.
    Button(&'a str),
    /// A binding on the rFLEX dead-man.
    Deadman(&'a str),
    /// A servo or joint two axes move.
    Target(&'a str),
}

impl Language {
    /// A gamepad conflict, in this language.
    pub fn pad_conflict(self, conflict: PadConflict<'_>) -> String {
        match (self, conflict) {
            (Self::English, PadConflict::Button(name)) => format!("{name} is bound more than once"),
            (Self::English, PadConflict::Deadman(name)) => format!("{name} is the dead-man button: it drives the base"),
            (Self::English, PadConflict::Target(name)) => format!("{name} is moved by more than one axis"),
            (Self::TraditionalChinese, PadConflict::Button(name)) => format!("{name} 綁定了不只一次"),
            (Self::TraditionalChinese, PadConflict::Deadman(name)) => format!("{name} 是安全鍵：它用來驅動底盤"),
            (Self::TraditionalChinese, PadConflict::Target(name)) => format!("{name} 被不只一個搖桿軸移動"),
        }
    }
}

/// How a family words what its devices say of themselves: each family's
/// `words.rs` submits one (`inventory::submit!`), for its own `Said`.
pub struct SaidWords(pub fn(&Identity, Language) -> Option<String>);

inventory::collect!(SaidWords);

/// What a device said, worded by its family (in English as the device layer says it
/// when the family words nothing).
impl Worded for Identity {
    fn worded(&self, language: Language) -> String {
        inventory::iter::<SaidWords>
            .into_iter()
            .find_map(|words| (words.0)(self, language))
            .unwrap_or_else(|| self.to_string())
    }
}

fn link_zh(link: &LinkReport) -> String {
    let ms = |d: Duration| d.as_secs_f64() * 1000.0;
    let Some(latency) = link.latency else { return "未量測".to_string() };
    let mut parts = vec![format!("第一個位元組 {:.1} ms 後到達", ms(latency))];
    if link.late > crate::device::plen2::CLUMP_GAP {
        parts.push(format!("最多延遲 {:.1} ms", ms(link.late)));
    }
    if !link.clump_gap.is_zero() {
        parts.push(format!("成批送達，間隔最長 {:.1} ms", ms(link.clump_gap)));
    } else if link.whole {
        parts.push("回覆整批送達".to_string());
    } else {
        parts.push("平順".to_string());
    }
    if let Some(rate) = link.bytes_per_s {
        parts.push(format!("每秒 {rate} 位元組"));
    }
    parts.join("、")
}
