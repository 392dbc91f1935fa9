//! How each field of a message goes on the wire and reads in the packet log:
//! one small codec per kind of field, named by the page's field names. The
//! message table (`message.rs`) says which codec each field uses; encoding,
//! decoding, the `result` byte and the log's words all follow from it.

use super::error::{ContentError, EncodeError};
use super::records::{
    ActionRecord, Coded, CommandType, JoystickTableRecord, ListEntry, MacroRecord, ServoMove, ServoParameter,
    ServoStatus, ServoSwitches, Stored,
};
use super::wire::{Reader, Writer};

/// `servoID` value that addresses every servo at once.
pub const ALL_SERVOS: u8 = 0xFF;

/// One kind of field: its bytes, and its words in the packet log.
pub(super) trait Codec<T> {
    /// Appends the value.
    fn write(&self, w: &mut Writer, value: &T) -> Result<(), EncodeError>;
    /// Reads the value.
    fn read(&self, r: &mut Reader<'_>) -> Result<T, ContentError>;
    /// The value as a person reads it (empty: nothing to say).
    fn words(&self, value: &T) -> String;
    /// The response's `result` byte, when this field is it.
    fn result(&self, _value: &T) -> Option<bool> {
        None
    }
}

/// A value the wire carries as is: a flag byte, a byte, a 16- or 32-bit number.
pub(super) trait Wire: Copy {
    /// Appends it.
    fn put(self, w: &mut Writer);
    /// Reads it from `field`.
    fn get(r: &mut Reader<'_>, field: &'static str) -> Result<Self, ContentError>;
}

macro_rules! wire {
    ($($ty:ty => $method:ident),*) => {
        $(impl Wire for $ty {
            fn put(self, w: &mut Writer) {
                w.$method(self);
            }
            fn get(r: &mut Reader<'_>, field: &'static str) -> Result<Self, ContentError> {
                r.$method(field)
            }
        })*
    };
}

wire!(bool => flag, u8 => u8, i16 => i16, i32 => i32, u32 => u32);

/// A plain field: its name on the page, how it reads in the log (with a
/// label), and — for a response's `result` byte — the result it carries.
pub(super) struct Plain<T> {
    field: &'static str,
    label: &'static str,
    words: fn(T, &'static str) -> String,
    result: fn(T) -> Option<bool>,
}

impl<T> Plain<T> {
    const fn new(field: &'static str, label: &'static str, words: fn(T, &'static str) -> String) -> Self {
        Self { field, label, words, result: |_| None }
    }
}

impl Plain<bool> {
    /// A response's `result` byte.
    pub(super) const fn outcome() -> Self {
        Self { result: Some, ..Self::new("result", "", |ok, _| (if ok { "ok" } else { "refused" }).into()) }
    }

    /// A byte that turns something on (1) or off (0).
    pub(super) const fn switch(field: &'static str) -> Self {
        Self::new(field, "", |on, _| (if on { "on" } else { "off" }).into())
    }
}

impl Plain<i32> {
    /// A 32-bit id (or number) of something, read as `label id`.
    pub(super) const fn id(field: &'static str, label: &'static str) -> Self {
        Self::new(field, label, |id, label| format!("{label} {id}"))
    }

    /// A memory size in bytes, read as `N bytes <what>`.
    pub(super) const fn bytes(field: &'static str, what: &'static str) -> Self {
        Self::new(field, what, |bytes, what| format!("{bytes} bytes {what}"))
    }
}

impl Plain<u8> {
    /// A `servoID` byte ([`ALL_SERVOS`] = every servo).
    pub(super) const fn servo_id() -> Self {
        Self::new("servoID", "", |servo_id, _| servo_words(servo_id))
    }
}

impl Plain<u32> {
    /// A remote button's 32-bit `buttonID`.
    pub(super) const fn button_id() -> Self {
        Self::new("buttonID", "", |button_id, _| format!("button 0x{button_id:08x}"))
    }
}

impl Plain<i16> {
    /// The remaining battery, ‰.
    pub(super) const fn permil() -> Self {
        Self::new("permil", "", |permil, _| format!("battery {:.1} %", f64::from(permil) / 10.0))
    }
}

impl<T: Wire> Codec<T> for Plain<T> {
    fn write(&self, w: &mut Writer, value: &T) -> Result<(), EncodeError> {
        value.put(w);
        Ok(())
    }
    fn read(&self, r: &mut Reader<'_>) -> Result<T, ContentError> {
        T::get(r, self.field)
    }
    fn words(&self, value: &T) -> String {
        (self.words)(*value, self.label)
    }
    fn result(&self, value: &T) -> Option<bool> {
        (self.result)(*value)
    }
}

fn servo_words(servo_id: u8) -> String {
    if servo_id == ALL_SERVOS { "all servos".into() } else { format!("servo {servo_id}") }
}

/// A one-byte code in `field`.
pub(super) struct Code(pub &'static str);

impl<T: Coded + Copy> Codec<T> for Code {
    fn write(&self, w: &mut Writer, value: &T) -> Result<(), EncodeError> {
        w.u8(value.code());
        Ok(())
    }
    fn read(&self, r: &mut Reader<'_>) -> Result<T, ContentError> {
        T::read(r, self.0)
    }
    fn words(&self, value: &T) -> String {
        value.words().into()
    }
}

/// A field the original page leaves out: present when bytes remain, absent
/// (`None`) when the content ends before it.
pub(super) struct Trailing<C>(pub C);

impl<T, C: Codec<T>> Codec<Option<T>> for Trailing<C> {
    fn write(&self, w: &mut Writer, value: &Option<T>) -> Result<(), EncodeError> {
        value.as_ref().map_or(Ok(()), |value| self.0.write(w, value))
    }
    fn read(&self, r: &mut Reader<'_>) -> Result<Option<T>, ContentError> {
        if r.remaining() == 0 { Ok(None) } else { self.0.read(r).map(Some) }
    }
    fn words(&self, value: &Option<T>) -> String {
        value.as_ref().map(|value| self.0.words(value)).unwrap_or_default()
    }
}

/// Whatever the content holds after what came before, kept as bytes.
pub(super) struct Rest;

impl Codec<Vec<u8>> for Rest {
    fn write(&self, w: &mut Writer, value: &Vec<u8>) -> Result<(), EncodeError> {
        w.bytes(value);
        Ok(())
    }
    fn read(&self, r: &mut Reader<'_>) -> Result<Vec<u8>, ContentError> {
        Ok(r.rest())
    }
    fn words(&self, value: &Vec<u8>) -> String {
        format!("{} byte(s)", value.len())
    }
}

/// `[servoCount] servoID`: a byte count, then one byte per servo.
pub(super) struct ServoIds;

impl Codec<Vec<u8>> for ServoIds {
    fn write(&self, w: &mut Writer, value: &Vec<u8>) -> Result<(), EncodeError> {
        w.count_u8("servoCount", value.len())?.bytes(value);
        Ok(())
    }
    fn read(&self, r: &mut Reader<'_>) -> Result<Vec<u8>, ContentError> {
        let count = usize::from(r.u8("servoCount")?);
        r.group("servoCount", count, 1, |r| r.u8("servoID"))
    }
    fn words(&self, value: &Vec<u8>) -> String {
        let ids: Vec<String> = value.iter().map(ToString::to_string).collect();
        format!("servos {}", ids.join(", "))
    }
}

/// An entry of fixed size that repeats in a group.
pub(super) trait Entry: Sized {
    /// Its bytes.
    const WIRE_LEN: usize;
    /// Reads one.
    fn read_entry(r: &mut Reader<'_>) -> Result<Self, ContentError>;
    /// Appends one.
    fn write_entry(&self, w: &mut Writer);
    /// One, in words.
    fn entry_words(&self) -> String;
    /// Between two entries in words.
    const SEPARATOR: &'static str = "; ";
}

impl Entry for ServoStatus {
    const WIRE_LEN: usize = ServoStatus::WIRE_LEN;
    const SEPARATOR: &'static str = ", ";
    fn read_entry(r: &mut Reader<'_>) -> Result<Self, ContentError> {
        ServoStatus::read(r)
    }
    fn write_entry(&self, w: &mut Writer) {
        self.write(w);
    }
    fn entry_words(&self) -> String {
        format!("servo {} at {}°", self.servo_id, self.angle)
    }
}

impl Entry for ServoMove {
    const WIRE_LEN: usize = ServoMove::WIRE_LEN;
    fn read_entry(r: &mut Reader<'_>) -> Result<Self, ContentError> {
        ServoMove::read(r)
    }
    fn write_entry(&self, w: &mut Writer) {
        self.write(w);
    }
    fn entry_words(&self) -> String {
        format!("servo {} → {}°, {} ms", self.servo_id, self.degree, i32::from(self.interval_10ms) * 10)
    }
}

impl Entry for ServoParameter {
    const WIRE_LEN: usize = ServoParameter::WIRE_LEN;
    fn read_entry(r: &mut Reader<'_>) -> Result<Self, ContentError> {
        ServoParameter::read(r)
    }
    fn write_entry(&self, w: &mut Writer) {
        self.write(w);
    }
    fn entry_words(&self) -> String {
        format!("servo {} {:?} offset {}°", self.servo_id, self.caption, self.adjusted_degree)
    }
}

fn group_words<T: Entry>(entries: &[T]) -> String {
    entries.iter().map(Entry::entry_words).collect::<Vec<_>>().join(T::SEPARATOR)
}

/// `[servoCount] {…}` with a one-byte count.
pub(super) struct ByteGroup;

impl<T: Entry> Codec<Vec<T>> for ByteGroup {
    fn write(&self, w: &mut Writer, value: &Vec<T>) -> Result<(), EncodeError> {
        w.count_u8("servoCount", value.len())?;
        value.iter().for_each(|entry| entry.write_entry(w));
        Ok(())
    }
    fn read(&self, r: &mut Reader<'_>) -> Result<Vec<T>, ContentError> {
        let count = usize::from(r.u8("servoCount")?);
        r.group("servoCount", count, T::WIRE_LEN, T::read_entry)
    }
    fn words(&self, value: &Vec<T>) -> String {
        group_words(value)
    }
}

/// `[servoCount] {…}` with a signed 16-bit count.
pub(super) struct WordGroup;

impl<T: Entry> Codec<Vec<T>> for WordGroup {
    fn write(&self, w: &mut Writer, value: &Vec<T>) -> Result<(), EncodeError> {
        w.count_i16("servoCount", value.len())?;
        value.iter().for_each(|entry| entry.write_entry(w));
        Ok(())
    }
    fn read(&self, r: &mut Reader<'_>) -> Result<Vec<T>, ContentError> {
        let count = r.count_i16("servoCount")?;
        r.group("servoCount", count, T::WIRE_LEN, T::read_entry)
    }
    fn words(&self, value: &Vec<T>) -> String {
        group_words(value)
    }
}

/// A list of ids and captions: count, id and caption field names.
pub(super) struct List(pub &'static str, pub &'static str, pub &'static str);

impl Codec<Vec<ListEntry>> for List {
    fn write(&self, w: &mut Writer, value: &Vec<ListEntry>) -> Result<(), EncodeError> {
        w.count_i16(self.0, value.len())?;
        value.iter().for_each(|entry| entry.write(w));
        Ok(())
    }
    fn read(&self, r: &mut Reader<'_>) -> Result<Vec<ListEntry>, ContentError> {
        let count = r.count_i16(self.0)?;
        r.group(self.0, count, ListEntry::WIRE_LEN, |r| ListEntry::read(r, self.1, self.2))
    }
    fn words(&self, value: &Vec<ListEntry>) -> String {
        let parts: Vec<String> = value.iter().map(|entry| format!("{} {:?}", entry.id, entry.caption)).collect();
        format!("{} item(s): {}", value.len(), parts.join(", "))
    }
}

/// A servo's run / hold switches.
pub(super) struct Switches;

impl Codec<ServoSwitches> for Switches {
    fn write(&self, w: &mut Writer, value: &ServoSwitches) -> Result<(), EncodeError> {
        value.write(w);
        Ok(())
    }
    fn read(&self, r: &mut Reader<'_>) -> Result<ServoSwitches, ContentError> {
        ServoSwitches::read(r)
    }
    fn words(&self, value: &ServoSwitches) -> String {
        format!(
            "{}: {}, {}",
            servo_words(value.servo_id),
            if value.is_start { "running" } else { "stopped" },
            if value.is_hold { "holding" } else { "released" }
        )
    }
}

/// A stored record in words.
pub(super) trait RecordWords: Stored {
    /// The record in words.
    fn record_words(&self) -> String;
}

impl RecordWords for ActionRecord {
    fn record_words(&self) -> String {
        format!("action {} {:?}: {}", self.action_id, self.caption, group_words(&self.steps))
    }
}

impl RecordWords for MacroRecord {
    fn record_words(&self) -> String {
        let commands: Vec<String> = self
            .commands
            .iter()
            .map(|c| {
                let what = match c.command_type {
                    CommandType::RunAction => format!("action {}", c.command_id),
                    CommandType::Delay => format!("wait {} ms", c.command_id),
                    CommandType::RunMacro => format!("macro {}", c.command_id),
                };
                format!("{what} at {} % × {}, total {} ms", c.ratio_percent, c.loop_count, c.total_interval_ms)
            })
            .collect();
        format!("macro {} {:?}: {}", self.macro_id, self.caption, commands.join("; "))
    }
}

impl RecordWords for JoystickTableRecord {
    fn record_words(&self) -> String {
        let buttons: Vec<String> = self
            .buttons
            .iter()
            .map(|b| {
                format!(
                    "0x{:08x} {:?}: press {}, long {}, release {}{}",
                    b.button_id,
                    b.caption,
                    b.press_macro,
                    b.long_press_macro,
                    b.up_macro,
                    if b.uninterruptible { ", uninterruptible" } else { "" }
                )
            })
            .collect();
        format!("table {} {:?}: {}", self.table_id, self.caption, buttons.join("; "))
    }
}

/// A whole stored record.
pub(super) struct Record;

impl<T: RecordWords> Codec<T> for Record {
    fn write(&self, w: &mut Writer, value: &T) -> Result<(), EncodeError> {
        value.write(w)
    }
    fn read(&self, r: &mut Reader<'_>) -> Result<T, ContentError> {
        let id = r.i32(T::ID_FIELD)?;
        T::read_after_id(r, id)
    }
    fn words(&self, value: &T) -> String {
        value.record_words()
    }
}

/// A record asked for by id: `None` when the board answered id 0 (not
/// found; whatever follows the id is arbitrary and ignored).
pub(super) struct Found;

impl<T: RecordWords> Codec<Option<T>> for Found {
    fn write(&self, w: &mut Writer, value: &Option<T>) -> Result<(), EncodeError> {
        match value {
            Some(record) => record.write(w),
            None => {
                // Failure: id 0, an empty caption and a count of 0.
                w.i32(0).str32("").i16(0);
                Ok(())
            }
        }
    }
    fn read(&self, r: &mut Reader<'_>) -> Result<Option<T>, ContentError> {
        match r.i32(T::ID_FIELD)? {
            0 => {
                let _ = r.rest();
                Ok(None)
            }
            id => T::read_after_id(r, id).map(Some),
        }
    }
    fn words(&self, value: &Option<T>) -> String {
        value.as_ref().map_or_else(|| "not found".into(), RecordWords::record_words)
    }
}
