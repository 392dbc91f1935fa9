//! The PLEN2 humanoid's protocol (`plen2.md`): ASCII commands with fixed-width
//! hexadecimal arguments, no terminator, no checksum, no acknowledgement; JSON
//! replies to the three getters, read until their brackets balance. Sans-IO.

mod command;
mod joint;
pub mod playback;
mod reply;

pub use command::{Command, CommandParser, MotionFrame, MotionHeader, ParseError, parse_commands};
pub use joint::*;
pub use reply::{
    JointSettingsReply, MAX_REPLY_BYTES, MotionReply, ReplyEvent, ReplyKind, ReplyReader, VersionReply,
    decode_joint_settings, decode_motion, decode_version,
};
