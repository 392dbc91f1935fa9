//! Every message of the servo board protocol (`board.md` §2) as a typed value,
//! with its encoding and decoding.

use super::error::{ContentError, EncodeError};
use super::frame::Frame;
use super::records::{
    ActionRecord, AngleUnit, ButtonEvent, JoystickTableRecord, ListEntry, MacroRecord, ServoMove, ServoParameter,
    ServoStatus, ServoSwitches, TransmissionMode,
};
use super::wire::{Reader, Writer};

/// `servoID` value that addresses every servo at once.
pub const ALL_SERVOS: u8 = 0xFF;

/// Every packet id the protocol defines, with its name, in the page's order.
pub const MESSAGE_TABLE: [(u16, &str); 60] = [
    (10010, "TransmissionModeSettingRequest"),
    (10011, "TransmissionModeSettingResponse"),
    (10020, "ClearAllDataRequest"),
    (10021, "ClearAllDataResponse"),
    (10030, "QueryMemorySizeRequest"),
    (10031, "QueryMemorySizeResponse"),
    (10040, "QueryRemainPowerRequest"),
    (10041, "QueryRemainPowerResponse"),
    (10050, "SendDummyDataRequest"),
    (20010, "QueryServoListRequest"),
    (20011, "QueryServoListResponse"),
    (20020, "QueryServoRequest"),
    (20021, "QueryServoResponse"),
    (20030, "SetServoParameterRequest"),
    (20031, "SetServoParameterResponse"),
    (20040, "SetAngleUnitRequest"),
    (20041, "SetAngleUnitResponse"),
    (20050, "ExecuteActionRequest"),
    (20060, "ExecuteActionExRequest"),
    (30010, "QueryActionListRequest"),
    (30011, "QueryActionListResponse"),
    (30020, "QueryActionRequest"),
    (30021, "QueryActionResponse"),
    (30030, "AddActionRequest"),
    (30031, "AddActionResponse"),
    (30040, "DeleteActionRequest"),
    (30041, "DeleteActionResponse"),
    (30050, "QueryMacroListRequest"),
    (30051, "QueryMacroListResponse"),
    (30060, "QueryMacroRequest"),
    (30061, "QueryMacroResponse"),
    (30070, "AddMacroRequest"),
    (30071, "AddMacroResponse"),
    (30080, "DeleteMacroRequest"),
    (30081, "DeleteMacroResponse"),
    (30090, "ExecuteMacroRequest"),
    (30091, "ExecuteMacroResponse"),
    (30100, "QueryServoParameterRequest"),
    (30101, "QueryServoParameterResponse"),
    (30110, "AddServoParameterRequest"),
    (30111, "AddServoParameterResponse"),
    (30120, "WriteProjectIDRequest"),
    (30121, "WriteProjectIDResponse"),
    (30130, "QueryProjectIDRequest"),
    (30131, "QueryProjectIDResponse"),
    (40010, "QueryJoystickTableListRequest"),
    (40011, "QueryJoystickTableListResponse"),
    (40020, "QueryJoystickTableRequest"),
    (40021, "QueryJoystickTableResponse"),
    (40030, "AddJoystickTableRequest"),
    (40031, "AddJoystickTableResponse"),
    (40040, "DeleteJoystickTableRequest"),
    (40041, "DeleteJoystickTableResponse"),
    (40050, "SetActiveJoystickTableRequest"),
    (40051, "SetActiveJoystickTableResponse"),
    (40060, "QueryActiveJoystickTableRequest"),
    (40061, "QueryActiveJoystickTableResponse"),
    (40070, "SubscribeButtonEventRequest"),
    (40071, "SubscribeButtonEventResponse"),
    (40081, "ButtonEventResponse"),
];

/// The protocol's name for a packet id, if the page defines it.
pub fn message_name(packet_id: u16) -> Option<&'static str> {
    MESSAGE_TABLE.iter().find(|(id, _)| *id == packet_id).map(|(_, name)| *name)
}

/// Whether a packet id is a request (ends in 0) rather than a response (decision D5).
pub fn is_request_id(packet_id: u16) -> bool {
    packet_id.is_multiple_of(10)
}

/// One message of the servo board protocol. Variant names are the page's names;
/// the doc comment of each gives its packet id.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Message {
    /// 10010: select the protocol generation.
    TransmissionModeSettingRequest {
        /// `mode`.
        mode: TransmissionMode,
    },
    /// 10011: the protocol generation now in use.
    TransmissionModeSettingResponse {
        /// `result`.
        mode: TransmissionMode,
    },
    /// 10020: erase everything the board stores.
    ClearAllDataRequest,
    /// 10021: result of the erase.
    ClearAllDataResponse {
        /// `result` (0 fail, anything else ok).
        ok: bool,
    },
    /// 10030: ask for the memory size.
    QueryMemorySizeRequest,
    /// 10031: free and total memory. The original page says length 4 (free only);
    /// a 4-byte content decodes with `total_bytes: None`.
    QueryMemorySizeResponse {
        /// `size`: free bytes.
        free_bytes: i32,
        /// `totalSize`: total bytes.
        total_bytes: Option<i32>,
    },
    /// 10040: ask for the remaining battery.
    QueryRemainPowerRequest,
    /// 10041: remaining battery.
    QueryRemainPowerResponse {
        /// `permil`: remaining battery in ‰.
        permil: i16,
    },
    /// 10050: test data, which the board discards (no response).
    SendDummyDataRequest {
        /// `data`.
        data: Vec<u8>,
    },
    /// 20010: ask for the servo list.
    QueryServoListRequest,
    /// 20011: the ids of the attached servos.
    QueryServoListResponse {
        /// `[servoCount] servoID`.
        servo_ids: Vec<u8>,
    },
    /// 20020: ask for one servo's state, or all ([`ALL_SERVOS`]).
    QueryServoRequest {
        /// `servoID`.
        servo_id: u8,
    },
    /// 20021: servo states (empty if the id is unknown).
    QueryServoResponse {
        /// `[servoCount] {...}`.
        servos: Vec<ServoStatus>,
    },
    /// 20030: set a servo's run / hold switches.
    SetServoParameterRequest(ServoSwitches),
    /// 20031: the switches now set.
    SetServoParameterResponse(ServoSwitches),
    /// 20040: set a servo's angle unit.
    SetAngleUnitRequest {
        /// `servoID` (0xFF = all).
        servo_id: u8,
        /// `unitType`.
        unit: AngleUnit,
    },
    /// 20041: the angle unit now set.
    SetAngleUnitResponse {
        /// `servoID`.
        servo_id: u8,
        /// `unitType`.
        unit: AngleUnit,
    },
    /// 20050: move servos now (no response).
    ExecuteActionRequest {
        /// `[servoCount] { servoID, degree, interval }`.
        moves: Vec<ServoMove>,
    },
    /// 20060: run a stored action (no response).
    ExecuteActionExRequest {
        /// `actionID`.
        action_id: i32,
    },
    /// 30010: ask for the action list.
    QueryActionListRequest,
    /// 30011: ids and captions of the stored actions.
    QueryActionListResponse {
        /// `[actionCount] { actionID, actionCaption }`.
        actions: Vec<ListEntry>,
    },
    /// 30020: ask for one action.
    QueryActionRequest {
        /// `actionID`.
        action_id: i32,
    },
    /// 30021: one action, or `None` when the board answered `actionID` 0 (failure).
    QueryActionResponse {
        /// The action.
        action: Option<ActionRecord>,
    },
    /// 30030: store an action.
    AddActionRequest(ActionRecord),
    /// 30031: result of the store.
    AddActionResponse {
        /// `result`.
        ok: bool,
    },
    /// 30040: delete an action.
    DeleteActionRequest {
        /// `actionID`.
        action_id: i32,
    },
    /// 30041: result of the delete.
    DeleteActionResponse {
        /// `result`.
        ok: bool,
    },
    /// 30050: ask for the macro list.
    QueryMacroListRequest,
    /// 30051: ids and captions of the stored macros.
    QueryMacroListResponse {
        /// `[macroCount] { macroID, macroCaption }`.
        macros: Vec<ListEntry>,
    },
    /// 30060: ask for one macro.
    QueryMacroRequest {
        /// `macroID`.
        macro_id: i32,
    },
    /// 30061: one macro, or `None` when the board answered `macroID` 0 (failure).
    QueryMacroResponse {
        /// The macro.
        macro_record: Option<MacroRecord>,
    },
    /// 30070: store a macro.
    AddMacroRequest(MacroRecord),
    /// 30071: result of the store.
    AddMacroResponse {
        /// `result`.
        ok: bool,
    },
    /// 30080: delete a macro.
    DeleteMacroRequest {
        /// `macroID`.
        macro_id: i32,
    },
    /// 30081: result of the delete.
    DeleteMacroResponse {
        /// `result`.
        ok: bool,
    },
    /// 30090: run a stored macro.
    ExecuteMacroRequest {
        /// `macroID`.
        macro_id: i32,
    },
    /// 30091: whether the macro started.
    ExecuteMacroResponse {
        /// `result`.
        ok: bool,
    },
    /// 30100: ask for the servo parameters.
    QueryServoParameterRequest,
    /// 30101: stored servo parameters (empty on error).
    QueryServoParameterResponse {
        /// `[servoCount] { servoID, adjustedDegree, servoCaption }`.
        servos: Vec<ServoParameter>,
    },
    /// 30110: store servo parameters.
    AddServoParameterRequest {
        /// `[servoCount] { servoID, adjustedDegree, servoCaption }`.
        servos: Vec<ServoParameter>,
    },
    /// 30111: result of the store.
    AddServoParameterResponse {
        /// `result`.
        ok: bool,
    },
    /// 30120: write the project id (overwrites).
    WriteProjectIdRequest {
        /// `projectID`.
        project_id: i32,
    },
    /// 30121: result of the write.
    WriteProjectIdResponse {
        /// `result`.
        ok: bool,
    },
    /// 30130: ask for the project id.
    QueryProjectIdRequest,
    /// 30131: the project id (0 = none).
    QueryProjectIdResponse {
        /// `projectID`.
        project_id: i32,
    },
    /// 40010: ask for the joystick table list.
    QueryJoystickTableListRequest,
    /// 40011: ids and captions of the stored tables.
    QueryJoystickTableListResponse {
        /// `[tableCount] { tableID, tableCaption }`.
        tables: Vec<ListEntry>,
    },
    /// 40020: ask for one joystick table.
    QueryJoystickTableRequest {
        /// `tableID`.
        table_id: i32,
    },
    /// 40021: one table, or `None` when the board answered `tableID` 0 (failure).
    QueryJoystickTableResponse {
        /// The table.
        table: Option<JoystickTableRecord>,
    },
    /// 40030: store a joystick table.
    AddJoystickTableRequest(JoystickTableRecord),
    /// 40031: result of the store.
    AddJoystickTableResponse {
        /// `result`.
        ok: bool,
    },
    /// 40040: delete a joystick table.
    DeleteJoystickTableRequest {
        /// `tableID`.
        table_id: i32,
    },
    /// 40041: result of the delete.
    DeleteJoystickTableResponse {
        /// `result`.
        ok: bool,
    },
    /// 40050: make a table the active one.
    SetActiveJoystickTableRequest {
        /// `tableID`.
        table_id: i32,
    },
    /// 40051: result.
    SetActiveJoystickTableResponse {
        /// `result`.
        ok: bool,
    },
    /// 40060: ask which table is active.
    QueryActiveJoystickTableRequest,
    /// 40061: the active table (0 = none).
    QueryActiveJoystickTableResponse {
        /// `tableID`.
        table_id: i32,
    },
    /// 40070: start or stop button events.
    SubscribeButtonEventRequest {
        /// `subscribe` (false = cancel).
        subscribe: bool,
    },
    /// 40071: result.
    SubscribeButtonEventResponse {
        /// `result`.
        ok: bool,
    },
    /// 40081: a button event, sent unsolicited while subscribed.
    ButtonEventResponse {
        /// `buttonID`.
        button_id: u32,
        /// `event`.
        event: ButtonEvent,
    },
    /// A packet id the page does not define (decision D6), kept as it came.
    Unknown {
        /// The packet id.
        packet_id: u16,
        /// The raw content.
        content: Vec<u8>,
    },
}

impl Message {
    /// The message's packet id.
    pub fn packet_id(&self) -> u16 {
        use Message as M;
        match self {
            M::TransmissionModeSettingRequest { .. } => 10010,
            M::TransmissionModeSettingResponse { .. } => 10011,
            M::ClearAllDataRequest => 10020,
            M::ClearAllDataResponse { .. } => 10021,
            M::QueryMemorySizeRequest => 10030,
            M::QueryMemorySizeResponse { .. } => 10031,
            M::QueryRemainPowerRequest => 10040,
            M::QueryRemainPowerResponse { .. } => 10041,
            M::SendDummyDataRequest { .. } => 10050,
            M::QueryServoListRequest => 20010,
            M::QueryServoListResponse { .. } => 20011,
            M::QueryServoRequest { .. } => 20020,
            M::QueryServoResponse { .. } => 20021,
            M::SetServoParameterRequest(_) => 20030,
            M::SetServoParameterResponse(_) => 20031,
            M::SetAngleUnitRequest { .. } => 20040,
            M::SetAngleUnitResponse { .. } => 20041,
            M::ExecuteActionRequest { .. } => 20050,
            M::ExecuteActionExRequest { .. } => 20060,
            M::QueryActionListRequest => 30010,
            M::QueryActionListResponse { .. } => 30011,
            M::QueryActionRequest { .. } => 30020,
            M::QueryActionResponse { .. } => 30021,
            M::AddActionRequest(_) => 30030,
            M::AddActionResponse { .. } => 30031,
            M::DeleteActionRequest { .. } => 30040,
            M::DeleteActionResponse { .. } => 30041,
            M::QueryMacroListRequest => 30050,
            M::QueryMacroListResponse { .. } => 30051,
            M::QueryMacroRequest { .. } => 30060,
            M::QueryMacroResponse { .. } => 30061,
            M::AddMacroRequest(_) => 30070,
            M::AddMacroResponse { .. } => 30071,
            M::DeleteMacroRequest { .. } => 30080,
            M::DeleteMacroResponse { .. } => 30081,
            M::ExecuteMacroRequest { .. } => 30090,
            M::ExecuteMacroResponse { .. } => 30091,
            M::QueryServoParameterRequest => 30100,
            M::QueryServoParameterResponse { .. } => 30101,
            M::AddServoParameterRequest { .. } => 30110,
            M::AddServoParameterResponse { .. } => 30111,
            M::WriteProjectIdRequest { .. } => 30120,
            M::WriteProjectIdResponse { .. } => 30121,
            M::QueryProjectIdRequest => 30130,
            M::QueryProjectIdResponse { .. } => 30131,
            M::QueryJoystickTableListRequest => 40010,
            M::QueryJoystickTableListResponse { .. } => 40011,
            M::QueryJoystickTableRequest { .. } => 40020,
            M::QueryJoystickTableResponse { .. } => 40021,
            M::AddJoystickTableRequest(_) => 40030,
            M::AddJoystickTableResponse { .. } => 40031,
            M::DeleteJoystickTableRequest { .. } => 40040,
            M::DeleteJoystickTableResponse { .. } => 40041,
            M::SetActiveJoystickTableRequest { .. } => 40050,
            M::SetActiveJoystickTableResponse { .. } => 40051,
            M::QueryActiveJoystickTableRequest => 40060,
            M::QueryActiveJoystickTableResponse { .. } => 40061,
            M::SubscribeButtonEventRequest { .. } => 40070,
            M::SubscribeButtonEventResponse { .. } => 40071,
            M::ButtonEventResponse { .. } => 40081,
            M::Unknown { packet_id, .. } => *packet_id,
        }
    }

    /// The protocol's name for this message (`"Unknown"` for an undefined id).
    pub fn name(&self) -> &'static str {
        message_name(self.packet_id()).unwrap_or("Unknown")
    }

    /// The `result` byte of a response that carries one (0 = failure), or
    /// `None` for every other message.
    pub fn result(&self) -> Option<bool> {
        use Message as M;
        match self {
            M::ClearAllDataResponse { ok }
            | M::AddActionResponse { ok }
            | M::DeleteActionResponse { ok }
            | M::AddMacroResponse { ok }
            | M::DeleteMacroResponse { ok }
            | M::ExecuteMacroResponse { ok }
            | M::AddServoParameterResponse { ok }
            | M::WriteProjectIdResponse { ok }
            | M::AddJoystickTableResponse { ok }
            | M::DeleteJoystickTableResponse { ok }
            | M::SetActiveJoystickTableResponse { ok }
            | M::SubscribeButtonEventResponse { ok } => Some(*ok),
            _ => None,
        }
    }

    /// The message's content bytes, fields in table order.
    pub fn encode_content(&self) -> Result<Vec<u8>, EncodeError> {
        use Message as M;
        let mut w = Writer::new(self.name());
        match self {
            M::TransmissionModeSettingRequest { mode } | M::TransmissionModeSettingResponse { mode } => {
                w.u8(mode.code());
            }
            M::ClearAllDataRequest
            | M::QueryMemorySizeRequest
            | M::QueryRemainPowerRequest
            | M::QueryServoListRequest
            | M::QueryActionListRequest
            | M::QueryMacroListRequest
            | M::QueryServoParameterRequest
            | M::QueryProjectIdRequest
            | M::QueryJoystickTableListRequest
            | M::QueryActiveJoystickTableRequest => {}
            M::ClearAllDataResponse { ok }
            | M::AddActionResponse { ok }
            | M::DeleteActionResponse { ok }
            | M::AddMacroResponse { ok }
            | M::DeleteMacroResponse { ok }
            | M::ExecuteMacroResponse { ok }
            | M::AddServoParameterResponse { ok }
            | M::WriteProjectIdResponse { ok }
            | M::AddJoystickTableResponse { ok }
            | M::DeleteJoystickTableResponse { ok }
            | M::SetActiveJoystickTableResponse { ok }
            | M::SubscribeButtonEventResponse { ok } => {
                w.flag(*ok);
            }
            M::QueryMemorySizeResponse { free_bytes, total_bytes } => {
                w.i32(*free_bytes);
                if let Some(total) = total_bytes {
                    w.i32(*total);
                }
            }
            M::QueryRemainPowerResponse { permil } => {
                w.i16(*permil);
            }
            M::SendDummyDataRequest { data } | M::Unknown { content: data, .. } => {
                w.bytes(data);
            }
            M::QueryServoListResponse { servo_ids } => {
                w.count_u8("servoCount", servo_ids.len())?.bytes(servo_ids);
            }
            M::QueryServoRequest { servo_id } => {
                w.u8(*servo_id);
            }
            M::QueryServoResponse { servos } => {
                w.count_u8("servoCount", servos.len())?;
                servos.iter().for_each(|servo| servo.write(&mut w));
            }
            M::SetServoParameterRequest(switches) | M::SetServoParameterResponse(switches) => {
                switches.write(&mut w);
            }
            M::SetAngleUnitRequest { servo_id, unit } | M::SetAngleUnitResponse { servo_id, unit } => {
                w.u8(*servo_id).u8(unit.code());
            }
            M::ExecuteActionRequest { moves } => {
                w.count_u8("servoCount", moves.len())?;
                moves.iter().for_each(|servo_move| servo_move.write(&mut w));
            }
            M::ExecuteActionExRequest { action_id: id }
            | M::QueryActionRequest { action_id: id }
            | M::DeleteActionRequest { action_id: id }
            | M::QueryMacroRequest { macro_id: id }
            | M::DeleteMacroRequest { macro_id: id }
            | M::ExecuteMacroRequest { macro_id: id }
            | M::WriteProjectIdRequest { project_id: id }
            | M::QueryProjectIdResponse { project_id: id }
            | M::QueryJoystickTableRequest { table_id: id }
            | M::DeleteJoystickTableRequest { table_id: id }
            | M::SetActiveJoystickTableRequest { table_id: id }
            | M::QueryActiveJoystickTableResponse { table_id: id } => {
                w.i32(*id);
            }
            M::QueryActionListResponse { actions: entries }
            | M::QueryMacroListResponse { macros: entries }
            | M::QueryJoystickTableListResponse { tables: entries } => {
                w.count_i16(list_count_field(self.packet_id()), entries.len())?;
                entries.iter().for_each(|entry| entry.write(&mut w));
            }
            M::QueryActionResponse { action: Some(action) } | M::AddActionRequest(action) => action.write(&mut w)?,
            M::QueryMacroResponse { macro_record: Some(record) } | M::AddMacroRequest(record) => {
                record.write(&mut w)?;
            }
            M::QueryJoystickTableResponse { table: Some(table) } | M::AddJoystickTableRequest(table) => {
                table.write(&mut w)?;
            }
            M::QueryActionResponse { action: None }
            | M::QueryMacroResponse { macro_record: None }
            | M::QueryJoystickTableResponse { table: None } => {
                // Failure: id 0, an empty caption and a count of 0.
                w.i32(0).str32("").i16(0);
            }
            M::QueryServoParameterResponse { servos } | M::AddServoParameterRequest { servos } => {
                w.count_i16("servoCount", servos.len())?;
                servos.iter().for_each(|servo| servo.write(&mut w));
            }
            M::SubscribeButtonEventRequest { subscribe } => {
                w.flag(*subscribe);
            }
            M::ButtonEventResponse { button_id, event } => {
                w.u32(*button_id).u8(event.code());
            }
        }
        Ok(w.finish())
    }

    /// The message as a frame.
    pub fn to_frame(&self) -> Result<Frame, EncodeError> {
        Ok(Frame::new(self.packet_id(), self.encode_content()?))
    }

    /// The message's complete wire bytes: header, content, checksum.
    pub fn encode(&self) -> Result<Vec<u8>, EncodeError> {
        self.to_frame()?.to_bytes()
    }

    /// Decodes a received frame. Undefined ids give [`Message::Unknown`].
    pub fn from_frame(frame: &Frame) -> Result<Self, ContentError> {
        Self::decode(frame.packet_id, &frame.content)
    }

    /// Decodes the content of a packet with the given id.
    pub fn decode(packet_id: u16, content: &[u8]) -> Result<Self, ContentError> {
        use Message as M;
        let Some(name) = message_name(packet_id) else {
            return Ok(M::Unknown { packet_id, content: content.to_vec() });
        };
        let mut r = Reader::new(name, content);
        let message = match packet_id {
            10010 => M::TransmissionModeSettingRequest { mode: TransmissionMode::read(&mut r, "mode")? },
            10011 => M::TransmissionModeSettingResponse { mode: TransmissionMode::read(&mut r, "result")? },
            10020 => M::ClearAllDataRequest,
            10021 => M::ClearAllDataResponse { ok: r.flag("result")? },
            10030 => M::QueryMemorySizeRequest,
            10031 => {
                let free_bytes = r.i32("size")?;
                // The original page gives length 4 (free size only): accept both.
                let total_bytes = if content.len() == 4 { None } else { Some(r.i32("totalSize")?) };
                M::QueryMemorySizeResponse { free_bytes, total_bytes }
            }
            10040 => M::QueryRemainPowerRequest,
            10041 => M::QueryRemainPowerResponse { permil: r.i16("permil")? },
            10050 => M::SendDummyDataRequest { data: r.rest() },
            20010 => M::QueryServoListRequest,
            20011 => {
                let count = usize::from(r.u8("servoCount")?);
                M::QueryServoListResponse { servo_ids: r.group("servoCount", count, 1, |r| r.u8("servoID"))? }
            }
            20020 => M::QueryServoRequest { servo_id: r.u8("servoID")? },
            20021 => {
                let count = usize::from(r.u8("servoCount")?);
                M::QueryServoResponse {
                    servos: r.group("servoCount", count, ServoStatus::WIRE_LEN, ServoStatus::read)?,
                }
            }
            20030 => M::SetServoParameterRequest(ServoSwitches::read(&mut r)?),
            20031 => M::SetServoParameterResponse(ServoSwitches::read(&mut r)?),
            20040 => M::SetAngleUnitRequest { servo_id: r.u8("servoID")?, unit: AngleUnit::read(&mut r, "unitType")? },
            20041 => M::SetAngleUnitResponse { servo_id: r.u8("servoID")?, unit: AngleUnit::read(&mut r, "unitType")? },
            20050 => {
                let count = usize::from(r.u8("servoCount")?);
                M::ExecuteActionRequest { moves: r.group("servoCount", count, ServoMove::WIRE_LEN, ServoMove::read)? }
            }
            20060 => M::ExecuteActionExRequest { action_id: r.i32("actionID")? },
            30010 => M::QueryActionListRequest,
            30011 => {
                M::QueryActionListResponse { actions: read_list(&mut r, "actionCount", "actionID", "actionCaption")? }
            }
            30020 => M::QueryActionRequest { action_id: r.i32("actionID")? },
            30021 => {
                let action_id = r.i32("actionID")?;
                if action_id == 0 {
                    // Failure: whatever follows the id is arbitrary.
                    return Ok(M::QueryActionResponse { action: None });
                }
                M::QueryActionResponse { action: Some(ActionRecord::read_after_id(&mut r, action_id)?) }
            }
            30030 => {
                let action_id = r.i32("actionID")?;
                M::AddActionRequest(ActionRecord::read_after_id(&mut r, action_id)?)
            }
            30031 => M::AddActionResponse { ok: r.flag("result")? },
            30040 => M::DeleteActionRequest { action_id: r.i32("actionID")? },
            30041 => M::DeleteActionResponse { ok: r.flag("result")? },
            30050 => M::QueryMacroListRequest,
            30051 => M::QueryMacroListResponse { macros: read_list(&mut r, "macroCount", "macroID", "macroCaption")? },
            30060 => M::QueryMacroRequest { macro_id: r.i32("macroID")? },
            30061 => {
                let macro_id = r.i32("macroID")?;
                if macro_id == 0 {
                    return Ok(M::QueryMacroResponse { macro_record: None });
                }
                M::QueryMacroResponse { macro_record: Some(MacroRecord::read_after_id(&mut r, macro_id)?) }
            }
            30070 => {
                let macro_id = r.i32("macroID")?;
                M::AddMacroRequest(MacroRecord::read_after_id(&mut r, macro_id)?)
            }
            30071 => M::AddMacroResponse { ok: r.flag("result")? },
            30080 => M::DeleteMacroRequest { macro_id: r.i32("macroID")? },
            30081 => M::DeleteMacroResponse { ok: r.flag("result")? },
            30090 => M::ExecuteMacroRequest { macro_id: r.i32("macroID")? },
            30091 => M::ExecuteMacroResponse { ok: r.flag("result")? },
            30100 => M::QueryServoParameterRequest,
            30101 => M::QueryServoParameterResponse { servos: read_servo_parameters(&mut r)? },
            30110 => M::AddServoParameterRequest { servos: read_servo_parameters(&mut r)? },
            30111 => M::AddServoParameterResponse { ok: r.flag("result")? },
            30120 => M::WriteProjectIdRequest { project_id: r.i32("projectID")? },
            30121 => M::WriteProjectIdResponse { ok: r.flag("result")? },
            30130 => M::QueryProjectIdRequest,
            30131 => M::QueryProjectIdResponse { project_id: r.i32("projectID")? },
            40010 => M::QueryJoystickTableListRequest,
            40011 => M::QueryJoystickTableListResponse {
                tables: read_list(&mut r, "tableCount", "tableID", "tableCaption")?,
            },
            40020 => M::QueryJoystickTableRequest { table_id: r.i32("tableID")? },
            40021 => {
                let table_id = r.i32("tableID")?;
                if table_id == 0 {
                    return Ok(M::QueryJoystickTableResponse { table: None });
                }
                M::QueryJoystickTableResponse { table: Some(JoystickTableRecord::read_after_id(&mut r, table_id)?) }
            }
            40030 => {
                let table_id = r.i32("tableID")?;
                M::AddJoystickTableRequest(JoystickTableRecord::read_after_id(&mut r, table_id)?)
            }
            40031 => M::AddJoystickTableResponse { ok: r.flag("result")? },
            40040 => M::DeleteJoystickTableRequest { table_id: r.i32("tableID")? },
            40041 => M::DeleteJoystickTableResponse { ok: r.flag("result")? },
            40050 => M::SetActiveJoystickTableRequest { table_id: r.i32("tableID")? },
            40051 => M::SetActiveJoystickTableResponse { ok: r.flag("result")? },
            40060 => M::QueryActiveJoystickTableRequest,
            40061 => M::QueryActiveJoystickTableResponse { table_id: r.i32("tableID")? },
            40070 => M::SubscribeButtonEventRequest { subscribe: r.flag("subscribe")? },
            40071 => M::SubscribeButtonEventResponse { ok: r.flag("result")? },
            40081 => M::ButtonEventResponse { button_id: r.u32("buttonID")?, event: ButtonEvent::read(&mut r)? },
            // Every id of MESSAGE_TABLE has an arm above; a table entry without
            // one is a programming error caught by the tests, reported here as unknown.
            _ => {
                return Ok(M::Unknown { packet_id, content: content.to_vec() });
            }
        };
        r.finish()?;
        Ok(message)
    }
}

fn list_count_field(packet_id: u16) -> &'static str {
    match packet_id {
        30011 => "actionCount",
        30051 => "macroCount",
        _ => "tableCount",
    }
}

fn read_list(
    r: &mut Reader<'_>,
    count_field: &'static str,
    id_field: &'static str,
    caption_field: &'static str,
) -> Result<Vec<ListEntry>, ContentError> {
    let count = r.count_i16(count_field)?;
    r.group(count_field, count, ListEntry::WIRE_LEN, |r| ListEntry::read(r, id_field, caption_field))
}

fn read_servo_parameters(r: &mut Reader<'_>) -> Result<Vec<ServoParameter>, ContentError> {
    let count = r.count_i16("servoCount")?;
    r.group("servoCount", count, ServoParameter::WIRE_LEN, ServoParameter::read)
}
