//! DYNAMIXEL servos' words that are not captions: what a servo says of
//! itself to the connection doctor, in the interface's language.

use crate::device::dynamixel::Said;
use crate::say;
use crate::ui::i18n::{Language, SaidWords, Worded};

/// What a servo said of itself, in this language.
impl Worded for Said {
    fn worded(&self, language: Language) -> String {
        if language == Language::English {
            return self.to_string();
        }
        let (id, protocol) = (self.id, self.protocol_name());
        match (self.model_name(), self.model) {
            (Some(model), Some((_, firmware))) => say!(language, "dynamixel_said.model", model, id, protocol, firmware),
            _ => say!(language, "dynamixel_said.servo", id, protocol),
        }
    }
}

inventory::submit! {
    SaidWords(|identity, language| identity.said::<Said>().map(|said| said.worded(language)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::device::dynamixel::Protocol;
    use crate::device::probe::Identity;

    #[test]
    fn a_servo_is_worded_in_chinese_by_its_family_and_in_english_by_the_device_layer() {
        let identity = Identity::new(Said { id: 3, protocol: Protocol::Two, model: Some((1020, 46)) });
        assert_eq!(
            identity.worded(Language::TraditionalChinese),
            "DYNAMIXEL XM430-W350 舵機，ID 3，Protocol 2.0，韌體 46"
        );
        assert_eq!(identity.worded(Language::English), "DYNAMIXEL XM430-W350, ID 3, Protocol 2.0, firmware 46");
    }
}
