//! Where in a project a problem is, said the way a person finds it.

use std::fmt;

/// Where in a project a problem is. Indices are 1-based, as a person counts.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Location {
    /// The project as a whole.
    Project,
    /// A servo.
    Servo {
        /// Its id.
        servo_id: u8,
        /// Its caption.
        caption: String,
    },
    /// An action.
    Action {
        /// Its id.
        action_id: i32,
        /// Its caption.
        caption: String,
    },
    /// One step of an action.
    Step {
        /// The action's id.
        action_id: i32,
        /// The action's caption.
        caption: String,
        /// The step's position, from 1.
        step: usize,
    },
    /// A macro.
    Macro {
        /// Its id.
        macro_id: i32,
        /// Its caption.
        caption: String,
    },
    /// One command of a macro.
    Command {
        /// The macro's id.
        macro_id: i32,
        /// The macro's caption.
        caption: String,
        /// The command's position, from 1.
        command: usize,
    },
    /// A joystick table.
    Table {
        /// Its id.
        table_id: i32,
        /// Its caption.
        caption: String,
    },
    /// A button of a joystick table.
    Button {
        /// The table's id.
        table_id: i32,
        /// The table's caption.
        table_caption: String,
        /// The button's id.
        button_id: u32,
        /// The button's caption.
        caption: String,
    },
    /// A PLEN2 joint's settings.
    Joint {
        /// The device map's name, e.g. `left_knee_pitch`.
        joint: &'static str,
    },
    /// A PLEN2 motion.
    Motion {
        /// Its slot (0..=89).
        slot: u8,
        /// Its name.
        name: String,
    },
    /// One frame of a PLEN2 motion.
    Frame {
        /// The motion's slot.
        slot: u8,
        /// The motion's name.
        name: String,
        /// The frame's position, from 1.
        frame: usize,
    },
    /// A PLEN2 play list.
    PlayList {
        /// Its position, from 1.
        index: usize,
        /// Its name.
        name: String,
    },
    /// The rFLEX robot settings.
    Robot,
    /// A gamepad button's binding.
    GamepadButton {
        /// Its code (`BTN_SOUTH` = 0x130, …).
        button: u16,
    },
    /// A gamepad axis's binding.
    GamepadAxis {
        /// Its code (`ABS_X` = 0, …).
        axis: u16,
    },
    /// A key of the file, by its path (`servo.servos[3].min_degs`).
    Key {
        /// Where it is, from the top of the file.
        path: String,
    },
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let q = |text| Shortened { text, quoted: true };
        match self {
            Self::Project => write!(f, "project"),
            Self::Servo { servo_id, caption } => write!(f, "servo {servo_id} {}", q(caption)),
            Self::Action { action_id, caption } => write!(f, "action {action_id} {}", q(caption)),
            Self::Step { action_id, caption, step } => write!(f, "action {action_id} {}, step {step}", q(caption)),
            Self::Macro { macro_id, caption } => write!(f, "macro {macro_id} {}", q(caption)),
            Self::Command { macro_id, caption, command } => {
                write!(f, "macro {macro_id} {}, command {command}", q(caption))
            }
            Self::Table { table_id, caption } => write!(f, "joystick table {table_id} {}", q(caption)),
            Self::Button { table_id, table_caption, button_id, caption } => {
                write!(f, "joystick table {table_id} {}, button 0x{button_id:08x} {}", q(table_caption), q(caption))
            }
            Self::Joint { joint } => write!(f, "joint {joint}"),
            Self::Motion { slot, name } => write!(f, "motion {slot} {}", q(name)),
            Self::Frame { slot, name, frame } => write!(f, "motion {slot} {}, frame {frame}", q(name)),
            Self::PlayList { index, name } => write!(f, "play list {index} {}", q(name)),
            Self::Robot => write!(f, "robot"),
            Self::GamepadButton { button } => write!(f, "gamepad button 0x{button:03x}"),
            Self::GamepadAxis { axis } => write!(f, "gamepad axis {axis}"),
            Self::Key { path } => write!(f, "{}", Shortened { text: path, quoted: false }),
        }
    }
}

/// At most this many characters of a caption or a key are shown in a
/// location; the rest is "…" (a 100,000-character caption is not echoed).
pub const SHOWN_CHARS: usize = 40;

/// Text cut to [`SHOWN_CHARS`] characters, in quotes (with escapes) when `quoted`.
struct Shortened<'a> {
    text: &'a str,
    quoted: bool,
}

impl fmt::Display for Shortened<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let cut = self.text.char_indices().nth(SHOWN_CHARS).map(|(at, _)| at);
        let shown = cut.map_or(self.text, |at| &self.text[..at]);
        let more = if cut.is_some() { "…" } else { "" };
        if self.quoted { write!(f, "{shown:?}{more}") } else { write!(f, "{shown}{more}") }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_caption_is_cut_where_a_location_is_shown() {
        let caption = "揮手".repeat(50_000);
        let shown = Location::Action { action_id: 3, caption }.to_string();
        assert_eq!(shown, format!("action 3 {:?}…", "揮手".repeat(20)));
        assert_eq!(Location::Servo { servo_id: 1, caption: "頭".into() }.to_string(), "servo 1 \"頭\"");
        let key = Location::Key { path: format!("servos[0].{}", "k".repeat(100)) }.to_string();
        assert_eq!(key, format!("servos[0].{}…", "k".repeat(30)));
    }
}
