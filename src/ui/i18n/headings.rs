//! Column headings of the editor's tables, in both languages.

use super::strings::Strings;

crate::words! {
    /// The words over the tables' columns.
    #[derive(Debug)]
    pub struct Headings in "headings" {
        /// "Step" (an action's step number).
        pub step: &'static str,
        /// "Angle".
        pub angle: &'static str,
        /// "Interval".
        pub interval: &'static str,
        /// "Command" (a macro's command number).
        pub command: &'static str,
        /// "Run".
        pub run: &'static str,
        /// "Repeat" (a command's ratio and loop).
        pub repeat: &'static str,
        /// "Duration".
        pub duration: &'static str,
        /// "Frame".
        pub frame: &'static str,
        /// "Motion".
        pub motion: &'static str,
        /// "Current" (the board's angle).
        pub current: &'static str,
    }
}

impl Strings {
    /// The tables' column headings.
    pub fn headings(&self) -> &'static Headings {
        Headings::of(self.lang)
    }
}
