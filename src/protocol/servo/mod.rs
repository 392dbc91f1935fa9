//! The servo controller board's packet protocol (`board.md`): frames with a
//! 4-byte magic, a little-endian packet id and length, content, and a byte-sum
//! checksum; 60 messages from 10010 to 40081.
//!
//! Sans-IO: nothing here reads or writes a port. [`FrameDecoder`] turns received
//! bytes into [`Frame`]s, [`Message::from_frame`] turns a frame into a typed
//! [`Message`], and [`Message::encode`] goes the other way.

mod codec;
mod decoder;
mod error;
mod frame;
mod message;
mod records;
mod store;
mod wire;

pub use decoder::{DecoderEvent, FrameDecoder, SkipReason};
pub use error::{ContentError, EncodeError};
pub use frame::{Frame, HEADER_LEN, MAGIC, MAX_CONTENT_LEN, OVERHEAD_LEN, checksum};
pub use message::{ALL_SERVOS, MESSAGE_TABLE, Message, is_request_id, message_name};
pub use records::{
    ActionRecord, AngleUnit, ButtonEvent, ButtonRecord, CommandType, JoystickTableRecord, ListEntry,
    MacroCommandRecord, MacroRecord, ServoMove, ServoParameter, ServoStatus, ServoSwitches, TransmissionMode,
};
pub use store::ServoImage;
pub use wire::{STR32_LEN, truncate_utf8};
