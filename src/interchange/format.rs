//! The formats other tools write, told from a file's content, and the error
//! a file that cannot be read as its format gives: where, and what is wrong.

/// A file format another tool writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Pololu Maestro Control Center's settings file (`<UscSettings>`).
    Maestro,
    /// ROBOTIS RoboPlus Motion 1.0 (`.mtn`, text).
    Mtn,
    /// ROBOTIS R+ Motion 2.0 (`.mtnx`, XML).
    Mtnx,
    /// The Blender servo-animation add-on's JSON export.
    Blender,
}

impl Format {
    /// Every format, in the order menus list them.
    pub const ALL: [Self; 4] = [Self::Maestro, Self::Mtn, Self::Mtnx, Self::Blender];

    /// The command line's word for it.
    pub fn tag(self) -> &'static str {
        match self {
            Self::Maestro => "maestro",
            Self::Mtn => "mtn",
            Self::Mtnx => "mtnx",
            Self::Blender => "blender",
        }
    }

    /// The format a command-line word names.
    pub fn from_tag(tag: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|format| format.tag().eq_ignore_ascii_case(tag))
    }

    /// What people call it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Maestro => "Maestro settings file",
            Self::Mtn => "RoboPlus Motion .mtn",
            Self::Mtnx => "R+ Motion .mtnx",
            Self::Blender => "Blender servo-animation JSON",
        }
    }

    /// The format a file's content shows, if any.
    pub fn guess(text: &str) -> Option<Self> {
        let start = text.trim_start_matches('\u{feff}').trim_start();
        if start.starts_with('{') {
            return blender_keys(start).then_some(Self::Blender);
        }
        if start.starts_with('<') {
            if text.contains("<UscSettings") {
                return Some(Self::Maestro);
            }
            let lower = text.to_ascii_lowercase();
            // R+ Motion names itself in its root; a file cut short still has that line.
            let marks = ["r+motion", "<designroot", "<flowroot", "<pageroot", "<page ", "<step "];
            return marks.iter().any(|mark| lower.contains(mark)).then_some(Self::Mtnx);
        }
        text.lines().any(|line| matches!(line.trim(), "page_begin" | "type=motion")).then_some(Self::Mtn)
    }
}

/// Whether a JSON object's top-level keys are the servo-animation add-on's
/// (`fps` with `servos`, `positions` or `pulses`), read even from a file cut short.
fn blender_keys(text: &str) -> bool {
    let keys: Vec<String> = match top_keys(text) {
        Some(keys) => keys,
        // Cut short or damaged: the keys named at the top level's indentation or anywhere.
        None => ["fps", "servos", "positions", "pulses"]
            .iter()
            .filter(|key| text.contains(&format!("\"{key}\"")))
            .map(ToString::to_string)
            .collect(),
    };
    let has = |key: &str| keys.iter().any(|k| k == key);
    has("fps") && (has("servos") || has("positions") || has("pulses"))
}

/// The keys of a JSON object's top level, none of their values kept; `None`
/// when the text is not a whole JSON object.
fn top_keys(text: &str) -> Option<Vec<String>> {
    use serde::Deserializer as _;
    use serde::de::{IgnoredAny, MapAccess, Visitor};
    struct Keys;
    impl<'de> Visitor<'de> for Keys {
        type Value = Vec<String>;
        fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str("an object")
        }
        fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Vec<String>, A::Error> {
            let mut keys = Vec::new();
            while let Some(key) = map.next_key::<String>()? {
                map.next_value::<IgnoredAny>()?;
                keys.push(key);
            }
            Ok(keys)
        }
    }
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let keys = deserializer.deserialize_map(Keys).ok()?;
    deserializer.end().ok().map(|()| keys)
}

/// A file that cannot be read as its format, and where.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}{}{message}", .line.map(|line| format!("line {line}: ")).unwrap_or_default(), .element.as_ref().map(|element| format!("<{element}>: ")).unwrap_or_default())]
pub struct ReadError {
    /// The line (from 1), when known.
    pub line: Option<usize>,
    /// The element (XML) or key (text, JSON) it is in.
    pub element: Option<String>,
    /// What is wrong and, where it helps, what to do.
    pub message: String,
}

impl ReadError {
    /// What to try about it: the line to fix, or taking the file again.
    pub fn what_to_try(&self, format: Format) -> String {
        let tool = match format {
            Format::Maestro => "Maestro Control Center",
            Format::Mtn => "RoboPlus Motion",
            Format::Mtnx => "R+ Motion",
            Format::Blender => "Blender",
        };
        if self.message.contains("cut short") {
            format!("take the whole file again, or save it again from {tool}")
        } else if let Some(line) = self.line {
            format!("correct line {line} in a text editor, or save the file again from {tool}")
        } else {
            format!("save the file again from {tool}")
        }
    }

    /// An error at `line` in `element`.
    pub fn at(line: usize, element: &str, message: impl Into<String>) -> Self {
        Self { line: Some(line), element: (!element.is_empty()).then(|| element.to_string()), message: message.into() }
    }
}

/// What to try when a file ends before its tool's last word.
pub(super) const CUT_SHORT: &str = "the file ends early: it was cut short (a copy or download broken off)";

impl From<super::xml::XmlError> for ReadError {
    fn from(error: super::xml::XmlError) -> Self {
        if error.too_much {
            return Self { line: Some(error.line), element: None, message: error.message };
        }
        let cut = ["end of input", "never closed", "unexpected end", "eof"]
            .iter()
            .any(|mark| error.message.to_ascii_lowercase().contains(mark));
        let hint = if cut { format!(" — {CUT_SHORT}") } else { String::new() };
        Self { line: Some(error.line), element: None, message: format!("not well-formed XML: {}{hint}", error.message) }
    }
}

/// A number in a file, or an error naming what it should have been.
/// A decimal comma ("1,5", as tools save on a decimal-comma locale) is read as a point.
pub(super) fn number(text: &str, line: usize, element: &str, what: &str) -> Result<f64, ReadError> {
    let trimmed = text.trim();
    let pointed = if trimmed.contains('.') { None } else { Some(trimmed.replacen(',', ".", 1)) };
    pointed
        .as_deref()
        .unwrap_or(trimmed)
        .parse::<f64>()
        .ok()
        .filter(|value| value.is_finite())
        .ok_or_else(|| ReadError::at(line, element, format!("{what} {text:?} is not a number")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_are_guessed_from_content() {
        assert_eq!(Format::guess("<!--Pololu-->\n<UscSettings version=\"1\">"), Some(Format::Maestro));
        assert_eq!(Format::guess("<?xml version=\"1.0\"?><Root><PageRoot>"), Some(Format::Mtnx));
        assert_eq!(Format::guess("type=motion\nversion=1.01\npage_begin"), Some(Format::Mtn));
        assert_eq!(Format::guess("\u{feff} {\"fps\": 30, \"positions\": [{\"0\": 1472}]}"), Some(Format::Blender));
        assert_eq!(Format::guess("{\"fps\": 30, \"pulses\": {\"Bone\": [\"3"), Some(Format::Blender));
        assert_eq!(Format::guess("{\"frames\": [{\"transition_time_ms\": 100}]}"), None);
        assert_eq!(
            Format::guess("<?xml version=\"1.0\"?>\n<Root name=\"R+Motion\" version=\"2.0.0\">\n  <Desi"),
            Some(Format::Mtnx)
        );
        assert_eq!(Format::guess("t_ms,a\n0,1"), None);
        assert_eq!(Format::from_tag("MTNX"), Some(Format::Mtnx));
    }

    #[test]
    fn decimal_commas_are_points_and_garbage_is_refused() {
        assert_eq!(number("1,5", 1, "step", "time"), Ok(1.5));
        assert_eq!(number(" 0,096", 1, "step", "time"), Ok(0.096));
        assert_eq!(number("1.5", 1, "step", "time"), Ok(1.5));
        assert!(number("1,5,0", 1, "step", "time").is_err());
        assert!(number("1.000,5", 1, "step", "time").is_err());
    }
}
