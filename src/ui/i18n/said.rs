//! Something said to the user (a status line, a line of a log), kept as
//! what it means: worded in every language when it is said, so that the
//! language chosen while it shows says it again in that language. Nothing
//! it was made from needs to live on (an error, a path): the words do.

use super::Language;

/// A sentence in every language (or one text for all: a path, a number, a
/// word from below the editor that has no translation).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Said {
    /// Each language's words, in [`Language::ALL`]'s order; one text for all when it has one entry.
    worded: Vec<String>,
}

impl Said {
    /// Worded by `word` in each language, now.
    pub fn new<T: Into<String>>(word: impl Fn(Language) -> T) -> Self {
        Self { worded: Language::ALL.iter().map(|&language| word(language).into()).collect() }
    }

    /// The same text in every language.
    pub fn fixed(text: impl Into<String>) -> Self {
        Self { worded: vec![text.into()] }
    }

    /// Its words in `language`.
    pub fn in_(&self, language: Language) -> &str {
        let index = Language::ALL.iter().position(|each| *each == language).unwrap_or(0);
        self.worded.get(index).or_else(|| self.worded.first()).map_or("", String::as_str)
    }

    /// The same, each language's words changed by `change`.
    pub fn map(&self, change: impl Fn(&str) -> String) -> Self {
        Self { worded: self.worded.iter().map(|text| change(text)).collect() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sentence_is_said_in_the_language_asked_and_a_fixed_text_in_all() {
        let stop = Said::new(|language| language.strings().stop);
        assert_eq!(stop.in_(Language::English), "STOP");
        assert_eq!(stop.in_(Language::Japanese), "停止");
        assert_eq!(stop.in_(Language::Korean), "정지");
        let path = Said::fixed("/home/skull.json");
        assert!(Language::ALL.iter().all(|&language| path.in_(language) == "/home/skull.json"));
        assert_eq!(stop.map(|text| format!("[{text}]")).in_(Language::TraditionalChinese), "[停止]");
    }
}
