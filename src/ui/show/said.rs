//! What the show says in the interface's language: why a show does not read
//! or play, how a run went, why passes did not join. The command line says
//! the same in English (the types' own `Display`).

use crate::remote::guard::{SHORTEST_TOKEN, ServeError};
use crate::say;
use crate::show::ShowError;
use crate::show::alive::{ASK_EVERY, Loss};
use crate::show::boards::{Told, Unlinked};
use crate::show::passes::JoinError;
use crate::show::play::{Ran, Stopped};
use crate::ui::i18n::{Language, Said, Worded};

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
            Self::PlaysInNoShow { device, lacks } => {
                say!(language, "show_said.plays_in_no_show", device, family = language.family(lacks.family))
            }
            Self::NotHeld { at_ms, device, family, .. } => {
                say!(language, "show_said.not_held", at_ms, device, family = language.family(*family))
            }
        }
    }
}

impl Worded for Loss {
    fn worded(&self, language: Language) -> String {
        match self {
            // The command line's own words.
            _ if language == Language::English => self.to_string(),
            Self::Link(reason) => language.disconnect_reason(reason),
            Self::Silent { quiet_ms } => say!(
                language,
                "show_said.silent_link",
                seconds = format!("{:.1}", Loss::seconds(*quiet_ms)),
                every = format!("{:.1}", ASK_EVERY.as_secs_f64())
            ),
            Self::Ended => say!(language, "show_said.link_ended"),
            Self::NoAnswer => say!(language, "show_said.no_answer"),
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
            // The editor's own STOP is named as its button is.
            Self::Asked(by) if by == "STOP" => say!(language, "show_said.stopped_by_stop"),
            Self::Asked(by) => say!(language, "show_said.stopped_by", by),
            Self::Lost { device, why } => say!(language, "show_said.lost", device, why = why.worded(language)),
            Self::Failed { device, why } => say!(language, "show_said.failed", device, why),
        }
    }
}

impl Worded for JoinError {
    fn worded(&self, language: Language) -> String {
        match self {
            Self::NoDevice(device) => say!(language, "show_said.no_pass_device", device),
            Self::Cannot { device, lacks } => {
                say!(language, "show_said.records_no_pass", device, family = language.family(lacks.family))
            }
            Self::TooShort => say!(language, "show_said.pass_too_short"),
            Self::TooLong(device) => say!(language, "show_said.passes_too_long", device),
            Self::NoSlot(device) => say!(language, "show_said.no_slot", device),
        }
    }
}

/// What a run did, a line each: every start (as its cue is captioned) and
/// how late it was written, every device played on without, and when it ended.
pub fn ran(ran: &Ran) -> Vec<Said> {
    let mut lines: Vec<Said> = ran
        .sent
        .iter()
        .map(|sent| {
            let (device, late_ms) = (&sent.device, sent.late_ms());
            super::said_by(|words| {
                let start = super::cues::cue_caption(&sent.start, None, words);
                say!(words.lang, "show_said.started", device, start, late_ms)
            })
        })
        .collect();
    for (device, why) in &ran.lost {
        lines.push(Said::new(|language| {
            say!(language, "show_said.played_on_without", device, why = why.worded(language))
        }));
    }
    let seconds = ran.ended.saturating_duration_since(ran.zero).as_secs_f64();
    lines.push(Said::new(|language| say!(language, "show_said.ended_after", seconds)));
    lines
}

/// What playing once (the boards not held) told, a line each.
pub fn told(told: &Told) -> Vec<Said> {
    match told {
        Told::Moved { device, port, opened } => {
            vec![Said::new(|language| say!(language, "show_said.port_moved", device, port, opened))]
        }
        Told::Answered { device, port, delay } => {
            let ms = delay.as_secs_f64() * 1000.0;
            vec![Said::new(|language| say!(language, "show_said.answered_on", device, port, ms))]
        }
        Told::Unlinked { device, port: None, why } => {
            vec![Said::new(|language| format!("{device}: {}", why.worded(language)))]
        }
        Told::Unlinked { device, port: Some(port), why } => vec![Said::new(|language| {
            say!(language, "show_said.did_not_answer_on", device, port, why = why.worded(language))
        })],
        Told::Silent(why) => vec![Said::new(|language| say!(language, "show_said.playing_silent", why))],
        Told::Ran(done) => ran(done),
        Told::Stopped(stopped) => vec![Said::new(|language| stopped.worded(language))],
    }
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
        // A device of a family that plays in no show, named in every language.
        let lacks = crate::show::family::Lacks {
            family: crate::project::Family::Plen2,
            lacks: crate::show::family::Capability::Show,
        };
        let plays_not = ShowError::PlaysInNoShow { device: "頭".into(), lacks };
        assert_eq!(
            plays_not.worded(Language::English),
            "device \"頭\": a PLEN2 cannot play in a show; remove it from the show"
        );
        assert_eq!(
            plays_not.worded(Language::TraditionalChinese),
            "裝置「頭」：PLEN2 無法在表演中演出，請將它從表演中移除"
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
        let stopped =
            Stopped::Lost { device: "arm".into(), why: Loss::Link(crate::link::DisconnectReason::ClosedByPeer) };
        assert_eq!(stopped.worded(Language::English), stopped.to_string());
        assert!(stopped.worded(Language::Korean).contains("arm"), "{}", stopped.worded(Language::Korean));
        // Why a device went is said in the language too, never in English inside it.
        let silent = Stopped::Lost { device: "arm".into(), why: Loss::silence(std::time::Duration::from_millis(2100)) };
        assert!(silent.to_string().contains("nothing came back for 2.1 s"), "{silent}");
        for language in [Language::Japanese, Language::Korean, Language::TraditionalChinese] {
            let said = silent.worded(language);
            assert!(said.contains("2.1") && !said.contains("answering"), "{language:?}: {said}");
        }
        assert_eq!(Loss::NoAnswer.worded(Language::Japanese), "応答しませんでした");
        let now = std::time::Instant::now();
        let sent = crate::show::play::Sent {
            device: "arm".into(),
            start: crate::show::Start::Macro(2),
            moving_at: now,
            due_at: now,
            sent_at: now,
            uncertain: std::time::Duration::ZERO,
            uncertain_of: "its link's spread",
        };
        let run = Ran { zero: now, sent: vec![sent], ended: now, with_sound: false, lost: Vec::new() };
        let said = ran(&run);
        let english: Vec<&str> = said.iter().map(|line| line.in_(Language::English)).collect();
        assert_eq!(english, ["arm started macro 2, 0.00 ms late", "ended after 0.00 s"]);
        assert_eq!(said[0].in_(Language::Japanese), "arm が マクロ 2 を開始、0.00 ms 遅れ");
    }

    /// What playing once tells is worded in English as the type says it, and in each language in its own words.
    #[test]
    fn playing_once_is_told_in_every_language() {
        let told = [
            Told::Moved { device: "arm".into(), port: "usb:0403:6001:A1".into(), opened: "/dev/ttyUSB1".into() },
            Told::Answered {
                device: "arm".into(),
                port: "/dev/ttyUSB1".into(),
                delay: std::time::Duration::from_micros(1500),
            },
            Told::Unlinked { device: "arm".into(), port: None, why: Unlinked::NoPort },
            Told::Unlinked {
                device: "arm".into(),
                port: Some("/dev/ttyUSB1".into()),
                why: Unlinked::Failed("timed out".into()),
            },
            Told::Silent("no server".into()),
            Told::Stopped(Stopped::Lost { device: "arm".into(), why: Loss::Ended }),
        ];
        for each in &told {
            let said = super::told(each);
            assert_eq!(said.len(), 1);
            assert_eq!(said[0].in_(Language::English), each.to_string());
            for language in [Language::Japanese, Language::Korean, Language::TraditionalChinese] {
                let words = said[0].in_(language);
                assert!(words.contains("arm") || words.contains("no server"), "{language:?}: {words}");
                assert_ne!(words, each.to_string(), "{language:?} says it in English");
            }
        }
        // The editor's STOP is named as its button is named in each language.
        let stopped = Stopped::Asked("STOP".into());
        assert_eq!(stopped.worded(Language::Korean), "정지 버튼으로 모든 장치를 정지했습니다");
        assert!(!stopped.worded(Language::Japanese).contains("STOP"));
    }
}
