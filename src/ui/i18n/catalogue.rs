//! A language's words, read from its one file in `assets/i18n/` (TOML: a
//! section per panel, a key per caption; a sentence's holes are `{name}`).
//! A word a language lacks falls back to English (and a test fails on it).

use std::collections::HashMap;
use std::fmt::{Display, Write as _};
use std::sync::OnceLock;

use super::Language;

/// One language's file, parsed once and kept for the process.
#[derive(Debug)]
pub struct Catalogue {
    /// The language the file is in.
    pub language: Language,
    /// The file's sections and keys.
    table: toml::Table,
}

impl Catalogue {
    /// `text` (a language's file) read; a file that does not parse is an
    /// empty catalogue (every word then falls back to English), and said on stderr.
    pub fn parse(language: Language, text: &str) -> Self {
        let table = text.parse::<toml::Table>().unwrap_or_else(|error| {
            eprintln!("servo-studio: the words of {language:?} do not read: {error}");
            toml::Table::new()
        });
        Self { language, table }
    }

    /// The catalogue of `language`, parsed on its first use (a language
    /// never shown is never parsed).
    pub fn of(language: Language) -> &'static Self {
        static CATALOGUES: [OnceLock<Catalogue>; Language::ALL.len()] =
            [const { OnceLock::new() }; Language::ALL.len()];
        CATALOGUES[language.index()].get_or_init(|| language.parsed())
    }

    /// The value at `key` ("section.name"), in this language only.
    pub fn value(&self, key: &str) -> Option<&toml::Value> {
        let (section, name) = key.split_once('.')?;
        self.table.get(section)?.as_table()?.get(name)
    }

    /// The value at `key` in this language, else in English.
    fn value_or_english(&'static self, key: &str) -> Option<&'static toml::Value> {
        self.value(key).or_else(|| Self::of(Language::English).value(key))
    }

    /// Every key of the file ("section.name"), in the file's order of sections.
    #[cfg(test)]
    pub fn keys(&self) -> Vec<String> {
        let mut keys = Vec::new();
        for (section, value) in &self.table {
            if let Some(table) = value.as_table() {
                keys.extend(table.keys().map(|name| format!("{section}.{name}")));
            }
        }
        keys
    }

    /// The text at `key` in this language, else in English.
    pub fn find(&'static self, key: &str) -> Option<&'static str> {
        self.value_or_english(key).and_then(toml::Value::as_str)
    }

    /// The text at `key`, else the English, else the key itself (seen, and failed by a test).
    pub fn text(&'static self, key: &str) -> &'static str {
        self.find(key).unwrap_or_else(|| missing(key))
    }
}

/// What stands for a word no language has: its key, leaked once per key.
fn missing(key: &str) -> &'static str {
    static SEEN: OnceLock<std::sync::Mutex<HashMap<String, &'static str>>> = OnceLock::new();
    let seen = SEEN.get_or_init(Default::default);
    let mut seen = seen.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    seen.entry(key.to_string()).or_insert_with(|| Box::leak(key.to_string().into_boxed_str()))
}

/// `template` with each `{name}` (or `{name:.N}`, N decimals) replaced by
/// the argument of that name; a hole with no argument is kept as it is. A
/// hole `{name|one|other}` is the word for that many (English's rule: see
/// [`fill_in`] for a language's own).
pub fn fill(template: &str, args: &[(&str, &dyn Display)]) -> String {
    fill_in(Language::English, template, args)
}

/// [`fill`], a count's word (`{count|frame|frames}`) chosen by `language`'s plural rule.
pub fn fill_in(language: Language, template: &str, args: &[(&str, &dyn Display)]) -> String {
    let mut out = String::with_capacity(template.len() + 16);
    let mut rest = template;
    while let Some(open) = rest.find('{') {
        out.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        let Some(close) = after.find('}') else {
            out.push_str(&rest[open..]);
            return out;
        };
        let hole = &after[..close];
        if let Some((name, forms)) = hole.split_once('|')
            && let Some((_, value)) = args.iter().find(|(arg, _)| *arg == name)
        {
            let (one, other) = forms.split_once('|').unwrap_or((forms, forms));
            out.push_str(if language.one(&value.to_string()) { one } else { other });
            rest = &after[close + 1..];
            continue;
        }
        let (name, decimals) = match hole.split_once(":.") {
            Some((name, decimals)) => (name, decimals.parse::<usize>().ok()),
            None => (hole, None),
        };
        // Writing to a String cannot fail.
        let _ = match (args.iter().find(|(arg, _)| *arg == name), decimals) {
            (Some((_, value)), Some(decimals)) => write!(out, "{value:.decimals$}"),
            (Some((_, value)), None) => write!(out, "{value}"),
            (None, _) => out.write_str(&rest[open..open + close + 2]),
        };
        rest = &after[close + 1..];
    }
    out.push_str(rest);
    out
}

/// The holes (`{name}`) a template asks for, in order, without their formats.
#[cfg(test)]
pub fn holes(template: &str) -> Vec<&str> {
    let mut names = Vec::new();
    let mut rest = template;
    while let Some(open) = rest.find('{') {
        let after = &rest[open + 1..];
        let Some(close) = after.find('}') else { break };
        names.push(after[..close].split([':', '|']).next().unwrap_or_default());
        rest = &after[close + 1..];
    }
    names
}

impl Language {
    /// The sentence at `key` in this language, its holes filled from `args`
    /// (usually through [`say!`](crate::say)).
    pub fn say(self, key: &str, args: &[(&str, &dyn Display)]) -> String {
        fill_in(self, Catalogue::of(self).text(key), args)
    }

    /// Whether `count` (as written) takes the word for one thing, by this
    /// language's plural rule: English, exactly 1; Chinese, Japanese and
    /// Korean have one form for every count (a counter word, not a plural).
    pub fn one(self, count: &str) -> bool {
        match self {
            Self::English => count.trim() == "1",
            Self::TraditionalChinese | Self::Japanese | Self::Korean => false,
        }
    }

    /// The caption at `key` in this language.
    pub fn word(self, key: &str) -> &'static str {
        Catalogue::of(self).text(key)
    }
}

/// A sentence in a language: `say!(language, "link.timed_out", port, timeout_ms = n)`
/// fills `{port}` from the variable `port` and `{timeout_ms}` from `n`.
#[macro_export]
macro_rules! say {
    ($language:expr, $key:literal $(, $name:ident $(= $value:expr)?)* $(,)?) => {
        $language.say($key, &[$((stringify!($name), &$crate::say!(@value $name $($value)?) as &dyn std::fmt::Display)),*])
    };
    (@value $name:ident) => { $name };
    (@value $name:ident $value:expr) => { $value };
}

/// What a field of a words table can be, read from a catalogue.
pub trait Word: Sized {
    /// The field at `key` of `catalogue`.
    fn read(catalogue: &'static Catalogue, key: &str) -> Self;
}

impl Word for &'static str {
    fn read(catalogue: &'static Catalogue, key: &str) -> Self {
        catalogue.text(key)
    }
}

impl Word for Language {
    fn read(catalogue: &'static Catalogue, _key: &str) -> Self {
        catalogue.language
    }
}

/// The strings of the array at `key` (an inner array's strings in turn).
fn strings(catalogue: &'static Catalogue, key: &str) -> Vec<&'static toml::Value> {
    catalogue
        .value_or_english(key)
        .and_then(toml::Value::as_array)
        .map(|array| array.iter().collect())
        .unwrap_or_default()
}

impl<const N: usize> Word for [&'static str; N] {
    fn read(catalogue: &'static Catalogue, key: &str) -> Self {
        let values = strings(catalogue, key);
        std::array::from_fn(|index| values.get(index).and_then(|value| value.as_str()).unwrap_or_else(|| missing(key)))
    }
}

/// A pair of strings from a two-element array.
fn pair(value: &'static toml::Value, key: &str) -> (&'static str, &'static str) {
    let pair = value.as_array().map(|array| array.as_slice()).unwrap_or_default();
    let at = |index: usize| pair.get(index).and_then(toml::Value::as_str).unwrap_or_else(|| missing(key));
    (at(0), at(1))
}

impl<const N: usize> Word for [(&'static str, &'static str); N] {
    fn read(catalogue: &'static Catalogue, key: &str) -> Self {
        let values = strings(catalogue, key);
        std::array::from_fn(|index| values.get(index).map_or((missing(key), missing(key)), |value| pair(value, key)))
    }
}

impl Word for &'static [(&'static str, &'static str)] {
    fn read(catalogue: &'static Catalogue, key: &str) -> Self {
        let values = catalogue.value(key).and_then(toml::Value::as_array).map(|array| array.as_slice());
        let pairs: Vec<_> = values.unwrap_or_default().iter().map(|value| pair(value, key)).collect();
        Box::leak(pairs.into_boxed_slice())
    }
}

/// A table of words (`words!`), for the test that every language has all of them.
#[derive(Debug)]
#[cfg_attr(not(test), allow(dead_code, reason = "read by the test of every language's words"))]
pub struct Table {
    /// The struct's name.
    pub name: &'static str,
    /// Its keys.
    pub keys: &'static [&'static str],
}

inventory::collect!(Table);

/// A table of words, one field per key of its section: the struct, its
/// `KEYS`, and `of(language)` (built once per language from its file).
#[macro_export]
macro_rules! words {
    (
        $(#[$meta:meta])*
        pub struct $name:ident in $section:literal {
            $($(#[$field_meta:meta])* pub $field:ident: $type:ty,)*
        }
    ) => {
        $(#[$meta])*
        pub struct $name {
            $($(#[$field_meta])* pub $field: $type,)*
        }

        impl $name {
            /// Every key of this table in a language's file.
            pub const KEYS: &'static [&'static str] = &[$(concat!($section, ".", stringify!($field))),*];

            /// The table in `language`, read from its file on first use.
            pub fn of(language: $crate::ui::i18n::Language) -> &'static Self {
                const LANGUAGES: usize = $crate::ui::i18n::Language::ALL.len();
                static TABLES: [std::sync::OnceLock<$name>; LANGUAGES] =
                    [const { std::sync::OnceLock::new() }; LANGUAGES];
                TABLES[language.index()].get_or_init(|| {
                    let catalogue = $crate::ui::i18n::Catalogue::of(language);
                    $name {
                        $($field: $crate::ui::i18n::Word::read(
                            catalogue,
                            concat!($section, ".", stringify!($field)),
                        ),)*
                    }
                })
            }
        }

        inventory::submit! { $crate::ui::i18n::Table { name: stringify!($name), keys: $name::KEYS } }
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_count_takes_its_word_by_each_languages_own_rule() {
        let template = "{count} {count|frame|frames}";
        let english: Vec<String> =
            [0, 1, 2, 21].iter().map(|count| fill_in(Language::English, template, &[("count", count)])).collect();
        assert_eq!(english, ["0 frames", "1 frame", "2 frames", "21 frames"]);
        assert_eq!(fill_in(Language::English, "{n|one|many}", &[("n", &1.5)]), "many", "1.5 is not one");
        for language in [Language::TraditionalChinese, Language::Japanese, Language::Korean] {
            assert!(!language.one("1") && !language.one("2"), "{language:?} has one form");
            assert_eq!(fill_in(language, "{n|a|b}", &[("n", &1)]), "b");
        }
        // Every catalogue's counts: English says "1 device", never "1 devices".
        let devices = |count: usize| crate::say!(Language::English, "show.device_count", count);
        assert_eq!((devices(1), devices(3)), ("1 device".to_string(), "3 devices".to_string()));
        assert_eq!(crate::say!(Language::Japanese, "show.device_count", count = 1), "1 台のデバイス");
    }

    #[test]
    fn holes_are_filled_by_name_with_decimals() {
        let (port, ms, degrees) = ("/dev/ttyUSB0", 500, 1.2345);
        let text =
            fill("{port}：{ms} ms、{degrees:.1}°、{unknown}", &[("port", &port), ("ms", &ms), ("degrees", &degrees)]);
        assert_eq!(text, "/dev/ttyUSB0：500 ms、1.2°、{unknown}");
        assert_eq!(holes("{a} and {b:.2} of {a}"), ["a", "b", "a"]);
        assert_eq!(fill("no close {brace", &[]), "no close {brace");
    }

    #[test]
    fn a_missing_word_falls_back_to_english_then_to_its_key() {
        let catalogue = Box::leak(Box::new(Catalogue::parse(Language::Japanese, "[strings]\nsave = \"保存\"\n")));
        assert_eq!(catalogue.text("strings.save"), "保存");
        assert_eq!(catalogue.text("strings.save_as"), Catalogue::of(Language::English).text("strings.save_as"));
        assert_eq!(catalogue.text("nowhere.at_all"), "nowhere.at_all");
    }
}
