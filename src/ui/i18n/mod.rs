//! The interface's words in English, 繁體中文, 日本語 and 한국어, chosen from
//! the OS locale and switchable at run time. Each language is one file,
//! `assets/i18n/<tag>.toml` (a section per panel, a key per caption, `{holes}`
//! in sentences), read by [`Catalogue`]; the tables of captions are built
//! from it (`words!`), and sentences are said with `say!`.

mod catalogue;
#[cfg(test)]
mod coverage;
mod doctor;
mod headings;
mod messages;
mod operations;
mod said;
mod strings;

#[cfg(test)]
use catalogue::holes;
pub use catalogue::{Catalogue, Table, Word, fill};
pub use doctor::{PadConflict, SaidWords};
pub use said::Said;
pub use strings::Strings;

/// Where the interface's language is kept in an egui context.
const CONTEXT_KEY: &str = "servo-studio-language";

/// A language of the interface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Language {
    /// English.
    #[default]
    English,
    /// 繁體中文.
    TraditionalChinese,
    /// 日本語.
    Japanese,
    /// 한국어.
    Korean,
}

impl Language {
    /// Every language, in menu order.
    pub const ALL: [Self; 4] = [Self::English, Self::TraditionalChinese, Self::Japanese, Self::Korean];

    /// Its place in [`Self::ALL`].
    pub const fn index(self) -> usize {
        self as usize
    }

    /// The language's file (`assets/i18n/`): its words, its name, and the locales it serves.
    fn file(self) -> &'static str {
        match self {
            Self::English => include_str!("../../../assets/i18n/en.toml"),
            Self::TraditionalChinese => include_str!("../../../assets/i18n/zh-Hant.toml"),
            Self::Japanese => include_str!("../../../assets/i18n/ja.toml"),
            Self::Korean => include_str!("../../../assets/i18n/ko.toml"),
        }
    }

    /// The locale prefixes the language serves, from its file's `[language]`
    /// section alone (the file's first: choosing a language parses no other's words).
    fn locales(self) -> Vec<String> {
        let head = self.file().split("\n[").take(2).collect::<Vec<_>>().join("\n[");
        let head: toml::Table = head.parse().unwrap_or_default();
        let locales = head.get("language").and_then(|language| language.get("locales")).and_then(toml::Value::as_array);
        locales.into_iter().flatten().filter_map(toml::Value::as_str).map(str::to_string).collect()
    }

    /// The language's file, parsed.
    fn parsed(self) -> Catalogue {
        Catalogue::parse(self, self.file())
    }

    /// The language the OS locale asks for: the one whose file lists a prefix
    /// of it (`zh_TW`, `zh-Hant`, `ja_JP`, `ko_KR`…), English otherwise.
    pub fn from_locale(locale: &str) -> Self {
        let locale = locale.to_ascii_lowercase().replace('-', "_");
        let serves = |language: &Self| {
            let whole = |prefix: &String| {
                // A whole part of the locale: `ko` serves `ko_KR`, not `kok_IN` (Konkani).
                let rest = locale.strip_prefix(prefix.as_str());
                rest.is_some_and(|rest| rest.chars().next().is_none_or(|c| matches!(c, '_' | '.' | '@')))
            };
            language.locales().iter().any(whole)
        };
        Self::ALL.into_iter().find(serves).unwrap_or(Self::English)
    }

    /// The language of this process's locale (`LC_ALL`, `LC_MESSAGES`, `LANG`).
    pub fn detect() -> Self {
        ["LC_ALL", "LC_MESSAGES", "LANG"]
            .iter()
            .filter_map(|name| std::env::var(name).ok())
            .find(|value| !value.is_empty())
            .map_or(Self::English, |locale| Self::from_locale(&locale))
    }

    /// The words of this language.
    pub fn strings(self) -> &'static Strings {
        Strings::of(self)
    }

    /// Puts this language in `ctx`, for the widgets drawn without the interface's words
    /// (written only when it changed: called every frame).
    pub fn put_in(self, ctx: &egui::Context) {
        if Self::in_context(ctx) != self {
            ctx.data_mut(|data| data.insert_temp(egui::Id::NULL.with(CONTEXT_KEY), self));
        }
    }

    /// The language put in `ctx` (English when none was).
    pub fn in_context(ctx: &egui::Context) -> Self {
        ctx.data(|data| data.get_temp(egui::Id::NULL.with(CONTEXT_KEY))).unwrap_or_default()
    }

    /// The language's own name ("日本語").
    pub fn name(self) -> &'static str {
        Catalogue::of(self).text("language.name")
    }
}

/// What words itself in the interface's language: an error or a notice,
/// worded next to the type that owns it (its family's or its layer's), not here.
pub trait Worded {
    /// It, in `language`.
    fn worded(&self, language: Language) -> String;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn link_errors_are_translated_with_what_to_try() {
        let error = crate::link::LinkError::PermissionDenied { port: "/dev/ttyUSB0".into() };
        assert!(Language::English.link_error(&error).contains("dialout"));
        let chinese = Language::TraditionalChinese.link_error(&error);
        assert!(chinese.starts_with("/dev/ttyUSB0：沒有權限") && chinese.contains("dialout"), "{chinese}");
    }

    #[test]
    fn file_errors_and_lost_links_are_whole_chinese_sentences() {
        let zh = Language::TraditionalChinese;
        let error = crate::project::LoadError::Syntax { line: 3, column: 5, message: "expected value".into() };
        assert_eq!(
            zh.load_error(std::path::Path::new("/tmp/機器人.json"), &error),
            "無法開啟 /tmp/機器人.json：第 3 行第 5 欄不是有效的專案內容"
        );
        let reason = crate::link::DisconnectReason::ReadFailed("Input/output error (os error 5)".into());
        let text = zh.link_ended(&reason);
        assert_eq!(
            text,
            "與控制板的連線已中斷（讀取連接埠失敗，線材是否被拔掉，或控制板斷電了）。專案未變更，準備好後請重新連線。"
        );
        assert!(!text.contains("os error"), "no English detail glued in");
        let english = Language::English.link_ended(&reason);
        assert_eq!(english.matches("cable").count(), 1, "the reason is said once: {english}");
    }

    /// Errors that used to reach the Chinese interface in English (or without
    /// their detail): a folder of motions that cannot be opened (a message
    /// that cannot be encoded: `ui::servo::words`).
    #[test]
    fn open_errors_keep_their_detail_in_chinese() {
        let zh = Language::TraditionalChinese;
        let folder = std::path::Path::new("/tmp/動作");
        let empty = crate::project::input::OpenError::Motion(crate::project::motion_json::MotionJsonError::Empty {
            path: folder.to_path_buf(),
        });
        assert_eq!(zh.open_error(folder, &empty), "/tmp/動作 裡沒有 motion.json（*.json）檔案");
        assert_eq!(Language::English.open_error(folder, &empty), "/tmp/動作 holds no motion.json (*.json) files");
    }

    /// The wording tables are split in two halves (a servo board's problems,
    /// and the rest): a problem of either half is worded in both languages.
    #[test]
    fn problems_of_both_halves_are_worded_in_both_languages() {
        use crate::project::ProblemKind as P;
        let kinds = [
            P::CaptionTooLong { bytes: 40 },
            P::StoredTotalDiffers { stored_ms: 10, derived_ms: 20 },
            P::RigCycle { path: vec![1, 2, 1] },
            P::UnknownKey,
        ];
        for kind in &kinds {
            let english = Language::English.problem(kind);
            let chinese = Language::TraditionalChinese.problem(kind);
            assert!(!english.is_empty() && english == kind.to_string(), "{kind:?}");
            assert!(!chinese.is_empty() && chinese != english, "{kind:?}: {chinese}");
        }
        assert!(Language::TraditionalChinese.problem(&kinds[2]).contains("1 → 2 → 1"));
    }

    #[test]
    fn locales_choose_the_language() {
        assert_eq!(Language::from_locale("zh_TW.UTF-8"), Language::TraditionalChinese);
        assert_eq!(Language::from_locale("zh-Hant-TW"), Language::TraditionalChinese);
        assert_eq!(Language::from_locale("zh_HK"), Language::TraditionalChinese);
        assert_eq!(Language::from_locale("en_US.UTF-8"), Language::English);
        assert_eq!(Language::from_locale("ja_JP.UTF-8"), Language::Japanese);
        assert_eq!(Language::from_locale("ko_KR.UTF-8"), Language::Korean);
        assert_eq!(Language::from_locale("zh_CN.UTF-8"), Language::English, "Simplified is not Traditional");
        assert_eq!(Language::from_locale("ja"), Language::Japanese);
        assert_eq!(Language::from_locale("kok_IN.UTF-8"), Language::English, "Konkani is not Korean");
        assert_eq!(Language::from_locale("C"), Language::English);
    }
}
