//! Drivers, one per board family, over a link: sessions, high-level operations
//! and a non-blocking handle each, all speaking typed events: [`servo`], the
//! servo controller board, and [`rflex`], mobile bases; PLEN2 joins as a sibling.
//!
//! What is shared by every family lives here: the line settings each family
//! needs, the family-neutral packet-log entry, and what long operations share
//! (cancel, backups, what a failed upload left).

pub mod dynamixel;
pub mod family;
mod operation;
pub mod plen2;
pub mod probe;
pub mod rflex;
pub mod servo;
pub mod speed;

pub use family::line_settings;
pub use operation::{Cancel, Left, Phase, Progress, Stage, UploadFailure, UploadSteps, backup_path, upload};

/// Which way a logged packet went.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Direction {
    /// Written to the board.
    Sent,
    /// Read from the board.
    Received,
    /// Bytes dropped while resynchronising.
    Skipped,
    /// What the driver decided (e.g. the pacing widened), not a packet.
    Note,
}

impl Direction {
    /// `→`, `←`, `!` or `·`.
    pub fn arrow(self) -> &'static str {
        match self {
            Self::Sent => "→",
            Self::Received => "←",
            Self::Skipped => "!",
            Self::Note => "·",
        }
    }
}

/// One packet-log entry, the same for every family: the driver turns its own
/// frames into these, and the log panel shows them.
#[derive(Clone, Debug, PartialEq)]
pub struct LogEntry {
    /// Seconds since the link opened.
    pub seconds: f64,
    /// Which way it went.
    pub direction: Direction,
    /// The message's name (`QueryServoRequest`, `>MF`, `MOT_AXIS_SET_DIR`…) or what was skipped.
    pub name: String,
    /// The fields as a person reads them: `servo 1 → 72°, 20 ms`.
    pub fields: String,
    /// The bytes, in hex.
    pub hex: String,
}

impl LogEntry {
    /// The entry as one line of text (for copying).
    pub fn line(&self) -> String {
        format!("{:9.3} {} {} {} [{}]", self.seconds, self.direction.arrow(), self.name, self.fields, self.hex)
    }
}

/// Bytes as space-separated hex pairs.
pub fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|byte| format!("{byte:02x}")).collect::<Vec<_>>().join(" ")
}

/// "1 byte", "2 bytes": a count of bytes as a message says it.
pub fn bytes(count: usize) -> String {
    if count == 1 { "1 byte".to_string() } else { format!("{count} bytes") }
}
