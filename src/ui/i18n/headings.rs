//! Column headings of the editor's tables, in both languages.

use super::Language;
use super::strings::Strings;

/// The words over the tables' columns.
#[derive(Debug)]
pub struct Headings {
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

const ENGLISH: Headings = Headings {
    step: "Step",
    angle: "Angle",
    interval: "Interval",
    command: "Command",
    run: "Run",
    repeat: "Repeat",
    duration: "Duration",
    frame: "Frame",
    motion: "Motion",
    current: "Current",
};

const TRADITIONAL_CHINESE: Headings = Headings {
    step: "步驟",
    angle: "角度",
    interval: "間隔",
    command: "指令",
    run: "執行",
    repeat: "重複",
    duration: "時間",
    frame: "影格",
    motion: "動作",
    current: "目前",
};

impl Strings {
    /// The tables' column headings.
    pub fn headings(&self) -> &'static Headings {
        match self.lang {
            Language::English => &ENGLISH,
            Language::TraditionalChinese => &TRADITIONAL_CHINESE,
        }
    }
}
