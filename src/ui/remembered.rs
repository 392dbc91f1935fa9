//! What the editor remembers between runs.

use std::path::PathBuf;

use crate::device::speed::LiveSpeed;
use crate::project::Family;
use crate::ui::i18n::Language;
use crate::ui::layout::Layout;

/// What is remembered between runs (the window's size and place are
/// remembered by eframe itself).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Remembered {
    /// Recent files, newest first.
    pub recent: Vec<PathBuf>,
    /// The interface language.
    pub language: Language,
    /// The tab shown, by name.
    pub tab: String,
    /// The board family last used.
    #[serde(default)]
    pub family: Family,
    /// How a PLEN2 is paced.
    #[serde(default)]
    pub plen2_pacing: crate::device::plen2::PacingMode,
    /// The live speed limit.
    #[serde(default)]
    pub live_speed: LiveSpeed,
    /// How each family's panels were laid out: servo, PLEN2, rFLEX.
    #[serde(default)]
    pub layouts: Vec<Layout>,
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use super::*;

    /// eframe's storage in memory.
    #[derive(Default)]
    struct Memory(HashMap<String, String>);

    impl eframe::Storage for Memory {
        fn get_string(&self, key: &str) -> Option<String> {
            self.0.get(key).cloned()
        }
        fn set_string(&mut self, key: &str, value: String) {
            self.0.insert(key.into(), value);
        }
        fn remove_string(&mut self, key: &str) {
            self.0.remove(key);
        }
        fn flush(&mut self) {}
    }

    #[test]
    fn what_an_earlier_version_stored_still_reads_and_what_is_stored_reads_back() {
        // Until 0.x the family was an enum, stored by eframe (RON) as a bare name.
        #[derive(serde::Serialize)]
        #[serde(rename_all = "lowercase")]
        enum Earlier {
            Plen2,
        }
        #[derive(serde::Serialize)]
        struct Stored {
            recent: Vec<PathBuf>,
            language: Language,
            tab: String,
            family: Earlier,
        }
        let mut storage = Memory::default();
        let earlier =
            Stored { recent: Vec::new(), language: Language::English, tab: "Motions".into(), family: Earlier::Plen2 };
        eframe::set_value(&mut storage, "earlier", &earlier);
        let stored = storage.0["earlier"].clone();
        assert!(stored.contains("family:plen2"), "stored as an earlier version did: {stored}");
        let read: Remembered = ron::from_str(&stored).expect("the earlier settings read");
        assert_eq!(eframe::get_value::<Remembered>(&storage, "earlier").as_ref(), Some(&read));
        assert_eq!(read.family, Family::Plen2);

        let now = Remembered { family: Family::Rflex, tab: "Drive".into(), ..Remembered::default() };
        eframe::set_value(&mut storage, "now", &now);
        assert_eq!(eframe::get_value::<Remembered>(&storage, "now"), Some(now));
        let json = serde_json::to_string(&Family::Plen2).unwrap();
        assert_eq!(json, "\"plen2\"");
        assert!(serde_json::from_str::<Family>("\"arm\"").unwrap_err().to_string().contains("one of servo, plen2"));
    }
}
