//! The graph pane's words, in both languages.

use crate::ui::i18n::Language;

crate::words! {
    /// Every caption of the graph pane.
    #[derive(Debug)]
    pub struct GraphWords in "graph" {
        /// The pane's title: "Graph".
        pub title: &'static str,
        /// "All" (show every channel).
        pub all: &'static str,
        /// "None" (hide every channel).
        pub none: &'static str,
        /// A channel's solo toggle: "Solo".
        pub solo: &'static str,
        /// Hover of a legend entry.
        pub toggle_hint: &'static str,
        /// "Copy curve".
        pub copy_curve: &'static str,
        /// "Paste curve".
        pub paste_curve: &'static str,
        /// "Curve" (the preset picker for the selected keys).
        pub curve: &'static str,
        /// Each preset's name, in `Easing::ALL` order, then a shaped curve's.
        pub presets: [&'static str; 6],
        /// "keys selected".
        pub selected: &'static str,
        /// How to work the graph (hover of the help mark).
        pub how: &'static str,
        /// The legend's entry for what the board plays: "dashed: what the board plays".
        pub baked: &'static str,
        /// The value axis: "Angle (°)".
        pub angle_axis: &'static str,
        /// A key's accessible name: "key".
        pub key: &'static str,
        /// A handle's accessible name: "handle".
        pub handle: &'static str,
    }
}

/// The graph's words in `language`.
pub fn words(language: Language) -> &'static GraphWords {
    GraphWords::of(language)
}
