//! Every message of the servo board protocol (`board.md` §2) as a typed
//! value, declared once in [`messages!`]: its packet id, the page's name,
//! and its fields with the codec of each. The enum, the id table, encoding,
//! decoding, the `result` byte and the packet log's words are all made from
//! that one table.

use super::codec::{ByteGroup, Code, Codec, Found, List, Plain, Record, Rest, ServoIds, Switches, Trailing, WordGroup};
use super::error::{ContentError, EncodeError};
use super::frame::Frame;
use super::records::{
    ActionRecord, AngleUnit, ButtonEvent, JoystickTableRecord, ListEntry, MacroRecord, ServoMove, ServoParameter,
    ServoStatus, ServoSwitches, TransmissionMode,
};
use super::wire::{Reader, Writer};

pub use super::codec::ALL_SERVOS;

/// Declares the protocol's messages. Each entry is
/// `ID Variant ["PageName"] { field: Type = Codec, … }`, `ID Variant(Type = Codec)`
/// or `ID Variant`; fields go on the wire in the order written.
macro_rules! messages {
    (@name $name:ident $wire:literal) => { $wire };
    (@name $name:ident) => { stringify!($name) };
    (@write $message:ident, $w:ident, $name:ident { $($field:ident = $codec:expr),* }) => {
        if let Message::$name { $($field),* } = $message {
            $( Codec::write(&$codec, &mut $w, $field)?; )*
        }
    };
    (@write $message:ident, $w:ident, $name:ident ( $codec:expr )) => {
        if let Message::$name(value) = $message {
            Codec::write(&$codec, &mut $w, value)?;
        }
    };
    (@write $message:ident, $w:ident, $name:ident) => { () };
    (@read $r:ident, $name:ident { $($field:ident = $codec:expr),* }) => {
        Message::$name { $($field: Codec::read(&$codec, &mut $r)?),* }
    };
    (@read $r:ident, $name:ident ( $codec:expr )) => { Message::$name(Codec::read(&$codec, &mut $r)?) };
    (@read $r:ident, $name:ident) => { Message::$name };
    (@result $message:ident, $name:ident { $($field:ident = $codec:expr),* }) => {{
        let mut result = None;
        if let Message::$name { $($field),* } = $message {
            $( result = result.or(Codec::result(&$codec, $field)); )*
        }
        result
    }};
    (@result $message:ident, $name:ident $( ( $codec:expr ) )?) => { None };
    (@words $message:ident, $name:ident { $($field:ident = $codec:expr),* }) => {{
        let mut parts: Vec<String> = Vec::new();
        if let Message::$name { $($field),* } = $message {
            $( parts.push(Codec::words(&$codec, $field)); )*
        }
        parts.retain(|part| !part.is_empty());
        parts.join(", ")
    }};
    (@words $message:ident, $name:ident ( $codec:expr )) => {
        if let Message::$name(value) = $message { Codec::words(&$codec, value) } else { String::new() }
    };
    (@words $message:ident, $name:ident) => { String::new() };
    (
        $(
            $(#[$doc:meta])*
            $id:literal $name:ident $($wire:literal)?
            $( { $( $(#[$field_doc:meta])* $field:ident : $ty:ty = $codec:expr ),* $(,)? } )?
            $( ( $tuple_ty:ty = $tuple_codec:expr ) )?
        ),* $(,)?
    ) => {
        /// One message of the servo board protocol. Variant names are the page's names;
        /// the doc comment of each gives its packet id.
        #[derive(Clone, Debug, PartialEq, Eq, Hash)]
        pub enum Message {
            $(
                $(#[$doc])*
                $name $( { $( $(#[$field_doc])* $field: $ty ),* } )? $( ($tuple_ty) )?,
            )*
            /// A packet id the page does not define (decision D6), kept as it came.
            Unknown {
                /// The packet id.
                packet_id: u16,
                /// The raw content.
                content: Vec<u8>,
            },
        }

        /// Every packet id the protocol defines, with its name, in the page's order.
        pub const MESSAGE_TABLE: [(u16, &str); [$($id),*].len()] = [$(($id, messages!(@name $name $($wire)?))),*];

        impl Message {
            /// The message's packet id.
            pub fn packet_id(&self) -> u16 {
                match self {
                    $( Self::$name { .. } => $id, )*
                    Self::Unknown { packet_id, .. } => *packet_id,
                }
            }

            /// The message's content bytes, fields in table order.
            pub fn encode_content(&self) -> Result<Vec<u8>, EncodeError> {
                let message = self;
                let mut w = Writer::new(self.name());
                match self {
                    $( Self::$name { .. } => {
                        messages!(@write message, w, $name $({ $($field = $codec),* })? $(($tuple_codec))?)
                    } )*
                    Self::Unknown { content, .. } => {
                        w.bytes(content);
                    }
                }
                Ok(w.finish())
            }

            /// Decodes the content of a packet with the given id.
            pub fn decode(packet_id: u16, content: &[u8]) -> Result<Self, ContentError> {
                let Some(name) = message_name(packet_id) else {
                    return Ok(Self::Unknown { packet_id, content: content.to_vec() });
                };
                let mut r = Reader::new(name, content);
                let message = match packet_id {
                    $( $id => messages!(@read r, $name $({ $($field = $codec),* })? $(($tuple_codec))?), )*
                    // Every id of MESSAGE_TABLE has an arm above.
                    _ => return Ok(Self::Unknown { packet_id, content: content.to_vec() }),
                };
                r.finish()?;
                Ok(message)
            }

            /// The `result` byte of a response that carries one (0 = failure), or
            /// `None` for every other message.
            pub fn result(&self) -> Option<bool> {
                let message = self;
                match self {
                    $( Self::$name { .. } => {
                        messages!(@result message, $name $({ $($field = $codec),* })? $(($tuple_codec))?)
                    } )*
                    Self::Unknown { .. } => None,
                }
            }

            /// The message's fields as a person reads them in the packet log
            /// (`servo 1 → 72°, 20 ms`).
            pub fn fields_in_words(&self) -> String {
                let message = self;
                match self {
                    $( Self::$name { .. } => {
                        messages!(@words message, $name $({ $($field = $codec),* })? $(($tuple_codec))?)
                    } )*
                    Self::Unknown { packet_id, content } => format!("id {packet_id}, {} byte(s)", content.len()),
                }
            }
        }
    };
}

messages! {
    /// 10010: select the protocol generation.
    10010 TransmissionModeSettingRequest {
        /// `mode`.
        mode: TransmissionMode = Code("mode"),
    },
    /// 10011: the protocol generation now in use.
    10011 TransmissionModeSettingResponse {
        /// `result`.
        mode: TransmissionMode = Code("result"),
    },
    /// 10020: erase everything the board stores.
    10020 ClearAllDataRequest,
    /// 10021: result of the erase.
    10021 ClearAllDataResponse {
        /// `result` (0 fail, anything else ok).
        ok: bool = Plain::outcome(),
    },
    /// 10030: ask for the memory size.
    10030 QueryMemorySizeRequest,
    /// 10031: free and total memory. The original page says length 4 (free only);
    /// a 4-byte content decodes with `total_bytes: None`.
    10031 QueryMemorySizeResponse {
        /// `size`: free bytes.
        free_bytes: i32 = Plain::bytes("size", "free"),
        /// `totalSize`: total bytes.
        total_bytes: Option<i32> = Trailing(Plain::bytes("totalSize", "in all")),
    },
    /// 10040: ask for the remaining battery.
    10040 QueryRemainPowerRequest,
    /// 10041: remaining battery.
    10041 QueryRemainPowerResponse {
        /// `permil`: remaining battery in ‰.
        permil: i16 = Plain::permil(),
    },
    /// 10050: test data, which the board discards (no response).
    10050 SendDummyDataRequest {
        /// `data`.
        data: Vec<u8> = Rest,
    },
    /// 20010: ask for the servo list.
    20010 QueryServoListRequest,
    /// 20011: the ids of the attached servos.
    20011 QueryServoListResponse {
        /// `[servoCount] servoID`.
        servo_ids: Vec<u8> = ServoIds,
    },
    /// 20020: ask for one servo's state, or all ([`ALL_SERVOS`]).
    20020 QueryServoRequest {
        /// `servoID`.
        servo_id: u8 = Plain::servo_id(),
    },
    /// 20021: servo states (empty if the id is unknown).
    20021 QueryServoResponse {
        /// `[servoCount] {...}`.
        servos: Vec<ServoStatus> = ByteGroup,
    },
    /// 20030: set a servo's run / hold switches.
    20030 SetServoParameterRequest(ServoSwitches = Switches),
    /// 20031: the switches now set.
    20031 SetServoParameterResponse(ServoSwitches = Switches),
    /// 20040: set a servo's angle unit.
    20040 SetAngleUnitRequest {
        /// `servoID` (0xFF = all).
        servo_id: u8 = Plain::servo_id(),
        /// `unitType`.
        unit: AngleUnit = Code("unitType"),
    },
    /// 20041: the angle unit now set.
    20041 SetAngleUnitResponse {
        /// `servoID`.
        servo_id: u8 = Plain::servo_id(),
        /// `unitType`.
        unit: AngleUnit = Code("unitType"),
    },
    /// 20050: move servos now (no response).
    20050 ExecuteActionRequest {
        /// `[servoCount] { servoID, degree, interval }`.
        moves: Vec<ServoMove> = ByteGroup,
    },
    /// 20060: run a stored action (no response).
    20060 ExecuteActionExRequest {
        /// `actionID`.
        action_id: i32 = Plain::id("actionID", "action"),
    },
    /// 30010: ask for the action list.
    30010 QueryActionListRequest,
    /// 30011: ids and captions of the stored actions.
    30011 QueryActionListResponse {
        /// `[actionCount] { actionID, actionCaption }`.
        actions: Vec<ListEntry> = List("actionCount", "actionID", "actionCaption"),
    },
    /// 30020: ask for one action.
    30020 QueryActionRequest {
        /// `actionID`.
        action_id: i32 = Plain::id("actionID", "action"),
    },
    /// 30021: one action, or `None` when the board answered `actionID` 0 (failure).
    30021 QueryActionResponse {
        /// The action.
        action: Option<ActionRecord> = Found,
    },
    /// 30030: store an action.
    30030 AddActionRequest(ActionRecord = Record),
    /// 30031: result of the store.
    30031 AddActionResponse {
        /// `result`.
        ok: bool = Plain::outcome(),
    },
    /// 30040: delete an action.
    30040 DeleteActionRequest {
        /// `actionID`.
        action_id: i32 = Plain::id("actionID", "action"),
    },
    /// 30041: result of the delete.
    30041 DeleteActionResponse {
        /// `result`.
        ok: bool = Plain::outcome(),
    },
    /// 30050: ask for the macro list.
    30050 QueryMacroListRequest,
    /// 30051: ids and captions of the stored macros.
    30051 QueryMacroListResponse {
        /// `[macroCount] { macroID, macroCaption }`.
        macros: Vec<ListEntry> = List("macroCount", "macroID", "macroCaption"),
    },
    /// 30060: ask for one macro.
    30060 QueryMacroRequest {
        /// `macroID`.
        macro_id: i32 = Plain::id("macroID", "macro"),
    },
    /// 30061: one macro, or `None` when the board answered `macroID` 0 (failure).
    30061 QueryMacroResponse {
        /// The macro.
        macro_record: Option<MacroRecord> = Found,
    },
    /// 30070: store a macro.
    30070 AddMacroRequest(MacroRecord = Record),
    /// 30071: result of the store.
    30071 AddMacroResponse {
        /// `result`.
        ok: bool = Plain::outcome(),
    },
    /// 30080: delete a macro.
    30080 DeleteMacroRequest {
        /// `macroID`.
        macro_id: i32 = Plain::id("macroID", "macro"),
    },
    /// 30081: result of the delete.
    30081 DeleteMacroResponse {
        /// `result`.
        ok: bool = Plain::outcome(),
    },
    /// 30090: run a stored macro.
    30090 ExecuteMacroRequest {
        /// `macroID`.
        macro_id: i32 = Plain::id("macroID", "macro"),
    },
    /// 30091: whether the macro started.
    30091 ExecuteMacroResponse {
        /// `result`.
        ok: bool = Plain::outcome(),
    },
    /// 30100: ask for the servo parameters.
    30100 QueryServoParameterRequest,
    /// 30101: stored servo parameters (empty on error).
    30101 QueryServoParameterResponse {
        /// `[servoCount] { servoID, adjustedDegree, servoCaption }`.
        servos: Vec<ServoParameter> = WordGroup,
    },
    /// 30110: store servo parameters.
    30110 AddServoParameterRequest {
        /// `[servoCount] { servoID, adjustedDegree, servoCaption }`.
        servos: Vec<ServoParameter> = WordGroup,
    },
    /// 30111: result of the store.
    30111 AddServoParameterResponse {
        /// `result`.
        ok: bool = Plain::outcome(),
    },
    /// 30120: write the project id (overwrites).
    30120 WriteProjectIdRequest "WriteProjectIDRequest" {
        /// `projectID`.
        project_id: i32 = Plain::id("projectID", "project"),
    },
    /// 30121: result of the write.
    30121 WriteProjectIdResponse "WriteProjectIDResponse" {
        /// `result`.
        ok: bool = Plain::outcome(),
    },
    /// 30130: ask for the project id.
    30130 QueryProjectIdRequest "QueryProjectIDRequest",
    /// 30131: the project id (0 = none).
    30131 QueryProjectIdResponse "QueryProjectIDResponse" {
        /// `projectID`.
        project_id: i32 = Plain::id("projectID", "project"),
    },
    /// 40010: ask for the joystick table list.
    40010 QueryJoystickTableListRequest,
    /// 40011: ids and captions of the stored tables.
    40011 QueryJoystickTableListResponse {
        /// `[tableCount] { tableID, tableCaption }`.
        tables: Vec<ListEntry> = List("tableCount", "tableID", "tableCaption"),
    },
    /// 40020: ask for one joystick table.
    40020 QueryJoystickTableRequest {
        /// `tableID`.
        table_id: i32 = Plain::id("tableID", "table"),
    },
    /// 40021: one table, or `None` when the board answered `tableID` 0 (failure).
    40021 QueryJoystickTableResponse {
        /// The table.
        table: Option<JoystickTableRecord> = Found,
    },
    /// 40030: store a joystick table.
    40030 AddJoystickTableRequest(JoystickTableRecord = Record),
    /// 40031: result of the store.
    40031 AddJoystickTableResponse {
        /// `result`.
        ok: bool = Plain::outcome(),
    },
    /// 40040: delete a joystick table.
    40040 DeleteJoystickTableRequest {
        /// `tableID`.
        table_id: i32 = Plain::id("tableID", "table"),
    },
    /// 40041: result of the delete.
    40041 DeleteJoystickTableResponse {
        /// `result`.
        ok: bool = Plain::outcome(),
    },
    /// 40050: make a table the active one.
    40050 SetActiveJoystickTableRequest {
        /// `tableID`.
        table_id: i32 = Plain::id("tableID", "table"),
    },
    /// 40051: result.
    40051 SetActiveJoystickTableResponse {
        /// `result`.
        ok: bool = Plain::outcome(),
    },
    /// 40060: ask which table is active.
    40060 QueryActiveJoystickTableRequest,
    /// 40061: the active table (0 = none).
    40061 QueryActiveJoystickTableResponse {
        /// `tableID`.
        table_id: i32 = Plain::id("tableID", "table"),
    },
    /// 40070: start or stop button events.
    40070 SubscribeButtonEventRequest {
        /// `subscribe` (false = cancel).
        subscribe: bool = Plain::switch("subscribe"),
    },
    /// 40071: result.
    40071 SubscribeButtonEventResponse {
        /// `result`.
        ok: bool = Plain::outcome(),
    },
    /// 40081: a button event, sent unsolicited while subscribed.
    40081 ButtonEventResponse {
        /// `buttonID`.
        button_id: u32 = Plain::button_id(),
        /// `event`.
        event: ButtonEvent = Code("event"),
    },
}

/// The protocol's name for a packet id, if the page defines it.
pub fn message_name(packet_id: u16) -> Option<&'static str> {
    MESSAGE_TABLE.iter().find(|(id, _)| *id == packet_id).map(|(_, name)| *name)
}

/// Whether a packet id is a request (ends in 0) rather than a response (decision D5).
pub fn is_request_id(packet_id: u16) -> bool {
    packet_id.is_multiple_of(10)
}

impl Message {
    /// The protocol's name for this message (`"Unknown"` for an undefined id).
    pub fn name(&self) -> &'static str {
        message_name(self.packet_id()).unwrap_or("Unknown")
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
}
