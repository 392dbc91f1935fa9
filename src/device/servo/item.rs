//! What an operation is working on, as data: shown in progress and named in
//! errors, and rendered by the interface in its own language. `Display` gives
//! the English text.

use std::fmt;

/// One step's subject.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Item {
    /// The project id (30130).
    ProjectId,
    /// The stored servo parameters (30100).
    ServoParameters,
    /// The action list (30010).
    ActionList,
    /// One action.
    Action {
        /// Its id.
        id: i32,
        /// Its caption.
        caption: String,
    },
    /// The macro list (30050).
    MacroList,
    /// One macro.
    Macro {
        /// Its id.
        id: i32,
        /// Its caption.
        caption: String,
    },
    /// The joystick table list (40010).
    TableList,
    /// One joystick table.
    Table {
        /// Its id.
        id: i32,
        /// Its caption.
        caption: String,
    },
    /// The active joystick table (40060).
    ActiveTable,
    /// The memory size (10030).
    MemorySize,
    /// Clearing everything (10020).
    ClearAll,
    /// Writing the project id (30120).
    WriteProjectId(i32),
    /// Writing this many servo parameters (30110).
    AddServoParameters(usize),
    /// Making this table the active one (40050).
    SetActiveTable(i32),
    /// A live move (20050).
    MoveServos,
    /// Running a stored action (20060).
    RunAction(i32),
    /// Running a stored macro (30090).
    RunMacro(i32),
    /// A servo's run / hold switches (20030).
    ServoSwitches(u8),
    /// A servo's angle unit (20040).
    AngleUnit(u8),
    /// A servo's live state (20020).
    ServoState(u8),
    /// The battery (10040).
    Battery,
    /// Button events (40070).
    ButtonEvents,
}

impl fmt::Display for Item {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::ProjectId => write!(f, "project id"),
            Self::ServoParameters => write!(f, "servo parameters"),
            Self::ActionList => write!(f, "action list"),
            Self::Action { id, caption } => write!(f, "action {id} {caption:?}"),
            Self::MacroList => write!(f, "macro list"),
            Self::Macro { id, caption } => write!(f, "macro {id} {caption:?}"),
            Self::TableList => write!(f, "joystick table list"),
            Self::Table { id, caption } => write!(f, "joystick table {id} {caption:?}"),
            Self::ActiveTable => write!(f, "active joystick table"),
            Self::MemorySize => write!(f, "memory size"),
            Self::ClearAll => write!(f, "clear all data"),
            Self::WriteProjectId(id) => write!(f, "project id {id}"),
            Self::AddServoParameters(count) => write!(f, "{count} servo parameter(s)"),
            Self::SetActiveTable(id) => write!(f, "active joystick table {id}"),
            Self::MoveServos => write!(f, "move servos"),
            Self::RunAction(id) => write!(f, "run action {id}"),
            Self::RunMacro(id) => write!(f, "run macro {id}"),
            Self::ServoSwitches(id) => write!(f, "servo {id} switches"),
            Self::AngleUnit(id) => write!(f, "servo {id} angle unit"),
            Self::ServoState(id) => write!(f, "servo {id} state"),
            Self::Battery => write!(f, "battery"),
            Self::ButtonEvents => write!(f, "button events"),
        }
    }
}
