//! What the PLEN2's driver is told and tells: its options, the commands of
//! its owner (sends, getters, live moves, STOP, the probe), what a reply
//! turns out to be, and why a reply did not come.

use std::time::Duration;

use crossbeam_channel::Sender;

use super::pacer::{Pacing, PacingMode, Widened};
use crate::device::LogEntry;
use crate::protocol::plen2::Command;

/// How long a reply may take to begin, or pause, before it is given up (the default).
pub const REPLY_IDLE: Duration = Duration::from_millis(600);

/// How the driver talks to one robot: the pacing mode and the firmware
/// timing it paces for, how long a getter's reply may take, and the line rate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Plen2Options {
    /// Fast, adaptive (the default) or the official tool's.
    pub mode: PacingMode,
    /// The firmware timing the pacer assumes.
    pub pacing: Pacing,
    /// How long the robot may take to begin a reply, and the longest silence
    /// inside one, on top of the reply's own time on the line.
    pub reply_timeout: Duration,
    /// The line rate (replies cannot arrive faster).
    pub line_baud: u32,
}

impl Default for Plen2Options {
    fn default() -> Self {
        Self { mode: PacingMode::Adaptive, pacing: Pacing::default(), reply_timeout: REPLY_IDLE, line_baud: 2_000_000 }
    }
}

/// A reply that did not come whole.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ReplyError {
    /// Nothing (or nothing more) came in time.
    #[error("no reply within {timeout_ms} ms: is the robot on, at 2,000,000 baud, with DTR asserted?")]
    Timeout {
        /// How long the reply was waited for, ms.
        timeout_ms: u64,
    },
    /// Bytes came, but no reply of the PLEN2's in them, before the reply's own
    /// time on the line had passed.
    #[error("the device answers, but not in the PLEN2's protocol ({} and no reply): is it a PLEN2?", crate::device::bytes(*.bytes))]
    NotThisProtocol {
        /// How many bytes came while waiting.
        bytes: usize,
    },
    /// So much came that it can only be garbage (a never-written slot).
    #[error("the reply was {} of garbage", crate::device::bytes(*.bytes))]
    Garbage {
        /// Its size.
        bytes: usize,
    },
    /// The link ended.
    #[error("the link to the robot was lost")]
    Disconnected,
    /// STOP was pressed while it still waited to be sent: it was not.
    #[error("STOP was pressed before it was sent: it was not sent")]
    Stopped,
}

/// Told when the robot should have finished a command (or that it was not sent).
pub type DoneSender = Sender<Result<(), ReplyError>>;

/// Where a reply goes.
pub type ReplySender = Sender<Result<Vec<u8>, ReplyError>>;

/// What the owner asks of the driver.
#[derive(Debug)]
pub enum Plen2Command {
    /// Send a command, paced; `done` is told when the robot should have finished it.
    Send {
        /// The command.
        command: Command,
        /// Told when the firmware is predicted idle again (or that STOP dropped it).
        done: Option<DoneSender>,
    },
    /// Send a getter and deliver its reply.
    Get {
        /// `<VI`, `<JS` or `<MO`.
        command: Command,
        /// Where the reply goes.
        reply: ReplySender,
        /// Told what the reply turns out to be while it is still arriving.
        news: Option<Sender<ReplyNews>>,
    },
    /// Joints to absolute angles (`$AN`), coalesced: the latest angle per device wins.
    LiveAngles(Vec<(u8, i16)>),
    /// STOP: `#RI` then `$HP`, ahead of everything queued; queued live moves are dropped.
    Stop,
    /// Bytes that end whatever command the firmware's parser may be stuck in
    /// (after lost bytes it can be waiting for arguments that never come):
    /// inside a command they are bad arguments, so it is dropped; between
    /// commands they are ignored.
    Resync,
    /// A slot read back different from what was written: the adaptive pacing
    /// widens its margins for the rest of the session.
    ReadBackDiffered,
    /// On connecting, and before an upload: if the adaptive pacing has not yet
    /// seen how the link delivers, read the version and the joint settings (a
    /// short reply, then one of about 1.7 KB) to see it; `reply` is told when
    /// that is done (at once when nothing is needed).
    Probe {
        /// Told when the link is known.
        reply: ReplySender,
    },
}

/// What a reply turns out to be, said while it still arrives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReplyNews {
    /// The slot was never written: the robot prints its erased EEPROM (about
    /// 300 KB, `plen2.md` §3) before it reads anything else.
    Erased {
        /// How long that is likely to take on this link, at the rate the
        /// reply's first bytes came (`None` until it can be told).
        remaining: Option<Duration>,
    },
}

/// The size a never-written slot's reply is reckoned at (plen2.md §3: 260–345 KB).
pub const ERASED_REPLY_BYTES: usize = 345 * 1024;

/// What [`Plen2Command::Resync`] sends: more than the longest command's arguments.
pub const RESYNC: &[u8; 110] = &[b'x'; 110];

/// What the driver reports.
#[derive(Clone, Debug, PartialEq)]
pub enum Plen2Event {
    /// A packet-log entry.
    Log(LogEntry),
    /// The adaptive pacing widened its margins.
    Widened(Widened),
}
