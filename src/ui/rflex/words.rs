//! The rFLEX base's words that are not captions: what a base says of itself
//! to the connection doctor, in the interface's language.

use crate::device::rflex::Said;
use crate::say;
use crate::ui::i18n::{Language, SaidWords, Worded};

/// What a base said of itself, in this language.
impl Worded for Said {
    fn worded(&self, language: Language) -> String {
        if language == Language::English {
            return self.to_string();
        }
        let volts = f64::from(self.voltage_raw) / 100.0;
        let brake = if self.braked { language.word("rflex_said.braked") } else { language.word("rflex_said.released") };
        say!(language, "rflex_said.base", volts, brake)
    }
}

inventory::submit! {
    SaidWords(|identity, language| identity.said::<Said>().map(|said| said.worded(language)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::device::probe::Identity;

    #[test]
    fn a_base_is_worded_in_chinese_by_its_family_and_in_english_by_the_device_layer() {
        let identity = Identity::new(Said { voltage_raw: 2415, braked: true });
        assert_eq!(identity.worded(Language::TraditionalChinese), "rFLEX 底盤，電池 24.15 V（原始值），煞車已鎖定");
        assert_eq!(identity.worded(Language::English), "rFLEX base, battery 24.15 V raw, brake set");
    }
}
