//! The compound values that several board messages share (`board.md` §2),
//! each with its own wire layout.

use super::error::{ContentError, EncodeError};
use super::wire::{Reader, Writer};

/// A one-byte code with a name for each value.
pub(crate) trait Coded: Sized {
    /// The byte.
    fn code(self) -> u8;
    /// Reads it from `field`.
    fn read(r: &mut Reader<'_>, field: &'static str) -> Result<Self, ContentError>;
    /// Its name.
    fn words(self) -> &'static str;
}

/// A record the board stores under an id: an action, a macro, a joystick table.
pub(crate) trait Stored: Sized {
    /// The id's field name.
    const ID_FIELD: &'static str;
    /// Reads the rest of the record after its id.
    fn read_after_id(r: &mut Reader<'_>, id: i32) -> Result<Self, ContentError>;
    /// Appends the whole record, id first.
    fn write(&self, w: &mut Writer) -> Result<(), EncodeError>;
}

/// A one-byte code: each value's byte and name once, and what a wrong byte should have been.
macro_rules! coded {
    ($ty:ident, $expected:literal, $($value:ident = $code:literal: $words:literal),* $(,)?) => {
        impl Coded for $ty {
            fn code(self) -> u8 {
                match self {
                    $(Self::$value => $code),*
                }
            }

            fn read(r: &mut Reader<'_>, field: &'static str) -> Result<Self, ContentError> {
                match r.u8(field)? {
                    $($code => Ok(Self::$value),)*
                    other => Err(r.invalid(field, $expected, i64::from(other))),
                }
            }

            fn words(self) -> &'static str {
                match self {
                    $(Self::$value => $words),*
                }
            }
        }
    };
}

coded!(AngleUnit, "0 (degree) or 1 (ADC)", Degree = 0: "angles in degrees", Adc = 1: "angles as ADC readings");
coded!(TransmissionMode, "0 (old) or 1 (new)", Old = 0: "old protocol", New = 1: "new protocol");
coded!(
    CommandType,
    "0 (action), 1 (delay) or 2 (macro)",
    RunAction = 0: "run an action",
    Delay = 1: "wait",
    RunMacro = 2: "run a macro",
);
coded!(
    ButtonEvent,
    "1 (press), 2 (long press) or 4 (release)",
    Press = 1: "press",
    LongPress = 2: "long press",
    Release = 4: "release",
);

/// Angle unit of a servo (20040 `unitType`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AngleUnit {
    /// `0`: angles are degrees.
    Degree,
    /// `1`: angles are raw ADC readings.
    Adc,
}

/// Protocol generation selected by 10010 (`mode`) and echoed by 10011 (`result`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TransmissionMode {
    /// `0`: the old protocol.
    Old,
    /// `1`: the new protocol (this one).
    New,
}

/// What a macro command runs (30061 `type`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CommandType {
    /// `0`: run the action whose id is `commandID`.
    RunAction,
    /// `1`: wait `commandID` milliseconds.
    Delay,
    /// `2`: run the macro whose id is `commandID`.
    RunMacro,
}

/// A remote-control button event (40081 `event`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ButtonEvent {
    /// `1`: the button went down.
    Press,
    /// `2`: the button has been held long.
    LongPress,
    /// `4`: the button came up.
    Release,
}

/// One servo's live state in 20021 (11 bytes).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct ServoStatus {
    /// `servoID`.
    pub servo_id: u8,
    /// `angle`, in degrees or ADC units depending on the servo's angle unit.
    pub angle: i16,
    /// `current`, raw ADC.
    pub current_adc: i16,
    /// `temperature`, raw ADC.
    pub temperature_adc: i16,
    /// `servoType`.
    pub servo_type: i16,
    /// `isStart`: the servo may run.
    pub is_start: bool,
    /// `isHold`: the servo holds torque.
    pub is_hold: bool,
}

impl ServoStatus {
    /// Bytes of one entry.
    pub const WIRE_LEN: usize = 11;

    pub(crate) fn read(r: &mut Reader<'_>) -> Result<Self, ContentError> {
        Ok(Self {
            servo_id: r.u8("servoID")?,
            angle: r.i16("angle")?,
            current_adc: r.i16("current")?,
            temperature_adc: r.i16("temperature")?,
            servo_type: r.i16("servoType")?,
            is_start: r.flag("isStart")?,
            is_hold: r.flag("isHold")?,
        })
    }

    pub(crate) fn write(&self, w: &mut Writer) {
        w.u8(self.servo_id)
            .i16(self.angle)
            .i16(self.current_adc)
            .i16(self.temperature_adc)
            .i16(self.servo_type)
            .flag(self.is_start)
            .flag(self.is_hold);
    }
}

/// Run / hold switches of one servo, or of all (`servo_id` 0xFF): 20030 and 20031.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ServoSwitches {
    /// `servoID` (0xFF = all servos).
    pub servo_id: u8,
    /// `isStart`: allow the servo to run.
    pub is_start: bool,
    /// `isHold`: hold torque.
    pub is_hold: bool,
}

impl ServoSwitches {
    pub(crate) fn read(r: &mut Reader<'_>) -> Result<Self, ContentError> {
        Ok(Self { servo_id: r.u8("servoID")?, is_start: r.flag("isStart")?, is_hold: r.flag("isHold")? })
    }

    pub(crate) fn write(&self, w: &mut Writer) {
        w.u8(self.servo_id).flag(self.is_start).flag(self.is_hold);
    }
}

/// One servo moving to an angle over a time: a step of an action (30021) or a
/// live move (20050). 5 bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ServoMove {
    /// `servoID`.
    pub servo_id: u8,
    /// `degree`: the target angle.
    pub degree: i16,
    /// `interval`: the time to reach it, in 10 ms (decision D7).
    pub interval_10ms: i16,
}

impl ServoMove {
    /// Bytes of one entry.
    pub const WIRE_LEN: usize = 5;

    pub(crate) fn read(r: &mut Reader<'_>) -> Result<Self, ContentError> {
        Ok(Self { servo_id: r.u8("servoID")?, degree: r.i16("degree")?, interval_10ms: r.i16("interval")? })
    }

    pub(crate) fn write(&self, w: &mut Writer) {
        w.u8(self.servo_id).i16(self.degree).i16(self.interval_10ms);
    }
}

/// An id and a caption: an entry of the action, macro and joystick table lists
/// (30011, 30051, 40011). 36 bytes.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct ListEntry {
    /// `actionID` / `macroID` / `tableID`.
    pub id: i32,
    /// `actionCaption` / `macroCaption` / `tableCaption`.
    pub caption: String,
}

impl ListEntry {
    /// Bytes of one entry.
    pub const WIRE_LEN: usize = 36;

    pub(crate) fn read(
        r: &mut Reader<'_>,
        id_field: &'static str,
        caption_field: &'static str,
    ) -> Result<Self, ContentError> {
        Ok(Self { id: r.i32(id_field)?, caption: r.str32(caption_field)? })
    }

    pub(crate) fn write(&self, w: &mut Writer) {
        w.i32(self.id).str32(&self.caption);
    }
}

/// A stored action: 30021 and 30030.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct ActionRecord {
    /// `actionID`.
    pub action_id: i32,
    /// `actionCaption`.
    pub caption: String,
    /// `[stepCount] { servoID, degree, interval }`; all steps start together.
    pub steps: Vec<ServoMove>,
}

impl Stored for ActionRecord {
    const ID_FIELD: &'static str = "actionID";

    fn read_after_id(r: &mut Reader<'_>, action_id: i32) -> Result<Self, ContentError> {
        let caption = r.str32("actionCaption")?;
        let count = r.count_i16("stepCount")?;
        let steps = r.group("stepCount", count, ServoMove::WIRE_LEN, ServoMove::read)?;
        Ok(Self { action_id, caption, steps })
    }

    fn write(&self, w: &mut Writer) -> Result<(), EncodeError> {
        w.i32(self.action_id).str32(&self.caption).count_i16("stepCount", self.steps.len())?;
        self.steps.iter().for_each(|step| step.write(w));
        Ok(())
    }
}

/// One command of a macro (12 bytes in 30061).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MacroCommandRecord {
    /// `commandID`: an action id, a delay in ms, or a macro id, by `command_type`.
    pub command_id: i32,
    /// `type`.
    pub command_type: CommandType,
    /// `ratio`: speed percentage, 1..100.
    pub ratio_percent: u8,
    /// `loop`: repetitions.
    pub loop_count: i16,
    /// `totalInterval`: the command's whole run time in ms.
    pub total_interval_ms: i32,
}

impl MacroCommandRecord {
    /// Bytes of one entry.
    pub const WIRE_LEN: usize = 12;

    fn read(r: &mut Reader<'_>) -> Result<Self, ContentError> {
        Ok(Self {
            command_id: r.i32("commandID")?,
            command_type: CommandType::read(r, "type")?,
            ratio_percent: r.u8("ratio")?,
            loop_count: r.i16("loop")?,
            total_interval_ms: r.i32("totalInterval")?,
        })
    }

    fn write(&self, w: &mut Writer) {
        w.i32(self.command_id)
            .u8(self.command_type.code())
            .u8(self.ratio_percent)
            .i16(self.loop_count)
            .i32(self.total_interval_ms);
    }
}

/// A stored macro: 30061 and 30070.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct MacroRecord {
    /// `macroID`.
    pub macro_id: i32,
    /// `macroCaption`.
    pub caption: String,
    /// `[commandCount]` commands, run one after another.
    pub commands: Vec<MacroCommandRecord>,
}

impl Stored for MacroRecord {
    const ID_FIELD: &'static str = "macroID";

    fn read_after_id(r: &mut Reader<'_>, macro_id: i32) -> Result<Self, ContentError> {
        let caption = r.str32("macroCaption")?;
        let count = r.count_i16("commandCount")?;
        let commands = r.group("commandCount", count, MacroCommandRecord::WIRE_LEN, MacroCommandRecord::read)?;
        Ok(Self { macro_id, caption, commands })
    }

    fn write(&self, w: &mut Writer) -> Result<(), EncodeError> {
        w.i32(self.macro_id).str32(&self.caption).count_i16("commandCount", self.commands.len())?;
        self.commands.iter().for_each(|command| command.write(w));
        Ok(())
    }
}

/// One servo's stored parameters in 30101 / 30110 (35 bytes).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct ServoParameter {
    /// `servoID`.
    pub servo_id: u8,
    /// `adjustedDegree`: the calibration offset.
    pub adjusted_degree: i16,
    /// `servoCaption`.
    pub caption: String,
}

impl ServoParameter {
    /// Bytes of one entry.
    pub const WIRE_LEN: usize = 35;

    pub(crate) fn read(r: &mut Reader<'_>) -> Result<Self, ContentError> {
        Ok(Self {
            servo_id: r.u8("servoID")?,
            adjusted_degree: r.i16("adjustedDegree")?,
            caption: r.str32("servoCaption")?,
        })
    }

    pub(crate) fn write(&self, w: &mut Writer) {
        w.u8(self.servo_id).i16(self.adjusted_degree).str32(&self.caption);
    }
}

/// One button of a joystick table (49 bytes in 40021).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct ButtonRecord {
    /// `buttonID`.
    pub button_id: u32,
    /// `buttonCaption`.
    pub caption: String,
    /// `buttonPressMacro` (0 = none).
    pub press_macro: i32,
    /// `buttonLongPressMacro` (0 = none).
    pub long_press_macro: i32,
    /// `buttonUpMacro` (0 = none).
    pub up_macro: i32,
    /// `uninterruptible`: a released long press lets its macro finish.
    pub uninterruptible: bool,
}

impl ButtonRecord {
    /// Bytes of one entry.
    pub const WIRE_LEN: usize = 49;

    fn read(r: &mut Reader<'_>) -> Result<Self, ContentError> {
        Ok(Self {
            button_id: r.u32("buttonID")?,
            caption: r.str32("buttonCaption")?,
            press_macro: r.i32("buttonPressMacro")?,
            long_press_macro: r.i32("buttonLongPressMacro")?,
            up_macro: r.i32("buttonUpMacro")?,
            uninterruptible: r.flag("uninterruptible")?,
        })
    }

    fn write(&self, w: &mut Writer) {
        w.u32(self.button_id)
            .str32(&self.caption)
            .i32(self.press_macro)
            .i32(self.long_press_macro)
            .i32(self.up_macro)
            .flag(self.uninterruptible);
    }
}

/// A stored joystick table: 40021 and 40030.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct JoystickTableRecord {
    /// `tableID`.
    pub table_id: i32,
    /// `tableCaption`.
    pub caption: String,
    /// `[buttonCount]` buttons.
    pub buttons: Vec<ButtonRecord>,
}

impl Stored for JoystickTableRecord {
    const ID_FIELD: &'static str = "tableID";

    fn read_after_id(r: &mut Reader<'_>, table_id: i32) -> Result<Self, ContentError> {
        let caption = r.str32("tableCaption")?;
        let count = r.count_i16("buttonCount")?;
        let buttons = r.group("buttonCount", count, ButtonRecord::WIRE_LEN, ButtonRecord::read)?;
        Ok(Self { table_id, caption, buttons })
    }

    fn write(&self, w: &mut Writer) -> Result<(), EncodeError> {
        w.i32(self.table_id).str32(&self.caption).count_i16("buttonCount", self.buttons.len())?;
        self.buttons.iter().for_each(|button| button.write(w));
        Ok(())
    }
}
