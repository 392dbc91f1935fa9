//! What the editor remembers between runs.

use std::path::PathBuf;

use crate::project::Family;
use crate::ui::i18n::Language;
use crate::ui::layout::Layout;
use crate::ui::speed::LiveSpeed;

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
