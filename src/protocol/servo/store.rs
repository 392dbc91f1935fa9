//! What a servo board stores, as its protocol records: the board's own
//! memory in the emulator, a backup read from a real board, what an upload
//! writes. Conversions to and from a project live with the driver
//! (`device::servo`); this knows only the protocol.

use super::{ActionRecord, EncodeError, JoystickTableRecord, MacroRecord, Message, ServoParameter};

/// Everything a servo board stores, in the order the board lists it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ServoImage {
    /// `projectID` (0 = none).
    pub project_id: i32,
    /// Stored servo parameters (30101).
    pub servos: Vec<ServoParameter>,
    /// Stored actions.
    pub actions: Vec<ActionRecord>,
    /// Stored macros, with `totalInterval` filled in.
    pub macros: Vec<MacroRecord>,
    /// Stored joystick tables.
    pub tables: Vec<JoystickTableRecord>,
    /// The active table (0 = none).
    pub active_table: i32,
}

impl ServoImage {
    /// The bytes these records occupy in board memory, as the emulated board
    /// counts them: the content of every add request, plus 4 bytes each for
    /// the project id and the active table id.
    pub fn footprint_bytes(&self) -> Result<usize, EncodeError> {
        let mut total = 8;
        if !self.servos.is_empty() {
            total += Message::AddServoParameterRequest { servos: self.servos.clone() }.encode_content()?.len();
        }
        for action in &self.actions {
            total += Message::AddActionRequest(action.clone()).encode_content()?.len();
        }
        for record in &self.macros {
            total += Message::AddMacroRequest(record.clone()).encode_content()?.len();
        }
        for table in &self.tables {
            total += Message::AddJoystickTableRequest(table.clone()).encode_content()?.len();
        }
        Ok(total)
    }
}
