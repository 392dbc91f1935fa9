//! What the show says in the interface's language: why a show does not read
//! or play, how a run went, why passes did not join. The command line says
//! the same in English (the types' own `Display`).

use super::ShowWords;
use crate::remote::guard::{SHORTEST_TOKEN, ServeError};
use crate::say;
use crate::show::ShowError;
use crate::show::boards::Unlinked;
use crate::show::passes::JoinError;
use crate::show::play::{Ran, Stopped};
use crate::ui::i18n::{Language, Worded};

impl Worded for ShowError {
    fn worded(&self, language: Language) -> String {
        match self {
            _ if language == Language::English => self.to_string(),
            Self::Load(error) => say!(language, "show_said.load", error = error.to_string()),
            Self::Json(why) => say!(language, "show_said.json", why),
            Self::NewerVersion { found } => {
                say!(language, "show_said.newer_version", found, max = crate::show::VERSION)
            }
            Self::DeviceProject { name, error } => {
                say!(language, "show_said.device_project", name, error = error.to_string())
            }
            Self::NoName(index) => say!(language, "show_said.no_name", index),
            Self::SameName(name) => say!(language, "show_said.same_name", name),
            Self::NoDevice { at_ms, device } => say!(language, "show_said.no_device", at_ms, device),
            Self::NotHeld { at_ms, device, family, .. } => {
                say!(language, "show_said.not_held", at_ms, device, family = language.family(*family))
            }
        }
    }
}

impl Worded for Unlinked {
    fn worded(&self, language: Language) -> String {
        match self {
            Self::NoPort => say!(language, "show_said.no_port"),
            // What the link said: its error, worded where it was made.
            Self::Failed(why) => why.clone(),
        }
    }
}

impl Worded for ServeError {
    fn worded(&self, language: Language) -> String {
        match self {
            _ if language == Language::English => self.to_string(),
            Self::NoToken { listen } => say!(language, "show_said.no_token", listen, shortest = SHORTEST_TOKEN),
            Self::TokenUnreadable { path, why } => {
                say!(language, "show_said.token_unreadable", file = path.display(), why)
            }
            Self::TokenTooShort { path } => {
                say!(language, "show_said.token_too_short", file = path.display(), shortest = SHORTEST_TOKEN)
            }
            Self::HttpTaken { at, why } => say!(language, "show_said.http_taken", at, why),
            Self::OscTaken { at, why } => say!(language, "show_said.osc_taken", at, why),
        }
    }
}

impl Worded for Stopped {
    fn worded(&self, language: Language) -> String {
        match self {
            Self::Asked(by) => say!(language, "show_said.stopped_by", by),
            Self::Lost { device, why } => say!(language, "show_said.lost", device, why),
            Self::Failed { device, why } => say!(language, "show_said.failed", device, why),
        }
    }
}

impl Worded for JoinError {
    fn worded(&self, language: Language) -> String {
        match self {
            Self::NoDevice(device) => say!(language, "show_said.no_pass_device", device),
            Self::TooShort => say!(language, "show_said.pass_too_short"),
            Self::TooLong(device) => say!(language, "show_said.passes_too_long", device),
            Self::NoSlot(device) => say!(language, "show_said.no_slot", device),
        }
    }
}

/// What a run did, a line each: every start (as its cue is captioned) and
/// how late it was written, every device played on without, and when it ended.
pub fn ran(ran: &Ran, words: &ShowWords) -> Vec<String> {
    let language = words.lang;
    let mut lines: Vec<String> = ran
        .sent
        .iter()
        .map(|sent| {
            let (device, start, late_ms) = (&sent.device, super::cue_caption(&sent.start, words), sent.late_ms());
            say!(language, "show_said.started", device, start, late_ms)
        })
        .collect();
    for (device, why) in &ran.lost {
        lines.push(say!(language, "show_said.played_on_without", device, why));
    }
    let seconds = ran.ended.saturating_duration_since(ran.zero).as_secs_f64();
    lines.push(say!(language, "show_said.ended_after", seconds));
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The English is the command line's, word for word; another language says it in its words.
    #[test]
    fn show_errors_say_the_command_lines_english_and_translate() {
        let error = ShowError::SameName("頭".into());
        assert_eq!(error.worded(Language::English), error.to_string());
        assert_eq!(
            error.worded(Language::Japanese),
            "「頭」という名前のデバイスが 2 つあります：名前は別々にしてください"
        );
        assert_eq!(Unlinked::NoPort.worded(Language::English), Unlinked::NoPort.to_string());
        assert_eq!(Unlinked::NoPort.worded(Language::Japanese), "ポートがありません：接続先を入力してください");
        let refused = ServeError::NoToken { listen: "0.0.0.0:8765".parse().unwrap() };
        assert_eq!(refused.worded(Language::English), refused.to_string());
        assert!(
            refused.worded(Language::Korean).starts_with("0.0.0.0:8765에서 수신하면"),
            "{}",
            refused.worded(Language::Korean)
        );
        let stopped = Stopped::Lost { device: "arm".into(), why: "EOF".into() };
        assert_eq!(stopped.worded(Language::English), stopped.to_string());
        assert!(stopped.worded(Language::Korean).contains("arm"), "{}", stopped.worded(Language::Korean));
        let now = std::time::Instant::now();
        let sent = crate::show::play::Sent {
            device: "arm".into(),
            start: crate::show::Start::Macro(2),
            moving_at: now,
            due_at: now,
            sent_at: now,
            uncertain: std::time::Duration::ZERO,
        };
        let run = Ran { zero: now, sent: vec![sent], ended: now, with_sound: false, lost: Vec::new() };
        let english = ran(&run, ShowWords::of(Language::English));
        assert_eq!(english, ["arm started macro 2, 0.00 ms late", "ended after 0.00 s"]);
        assert_eq!(ran(&run, ShowWords::of(Language::Japanese))[0], "arm が マクロ 2 を開始、0.00 ms 遅れ");
    }
}
