//! A packet on the bus as the packet log keeps it: small enough to travel
//! with the driver's other events, worded when the log panel shows it.

use std::time::Instant;

use super::Protocol;
use crate::device::Direction;
use crate::protocol::dynamixel::{Kind, Packet};

/// A packet on the bus, for the packet log: which way it went, what it was,
/// and its first bytes (a long sync write is shown cut).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Logged {
    /// Seconds since the link opened.
    pub seconds: f64,
    /// Sent, received, or bytes skipped.
    pub direction: Direction,
    /// The packet's protocol, ID, kind and parameter count (none: bytes that were no packet).
    pub packet: Option<(Protocol, u8, Kind, usize)>,
    /// Its first bytes.
    pub head: [u8; 24],
    /// How many of `head` are its bytes.
    pub shown: u8,
    /// How many bytes it had in all.
    pub total: usize,
    /// Why bytes were skipped.
    pub why: &'static str,
}

impl Logged {
    /// `bytes` of `total` (a packet's, or ones that were none and `why`), gone
    /// `direction` at `now`, on a link first heard of at `opened`.
    pub(super) fn of(
        (opened, now): (Instant, Instant),
        direction: Direction,
        packet: Option<&Packet>,
        (bytes, total): (&[u8], usize),
        why: &'static str,
    ) -> Self {
        let mut head = [0; 24];
        let shown = bytes.len().min(head.len());
        head[..shown].copy_from_slice(&bytes[..shown]);
        Self {
            seconds: now.saturating_duration_since(opened).as_secs_f64(),
            direction,
            packet: packet.map(|packet| (packet.protocol, packet.id, packet.kind, packet.params.len())),
            head,
            shown: u8::try_from(shown).unwrap_or(u8::MAX),
            total,
            why,
        }
    }

    /// A packet-log entry, as the log panel shows it.
    pub fn entry(&self) -> crate::device::LogEntry {
        use crate::protocol::dynamixel::{Kind, instruction as i};
        let mut hex = crate::device::hex(&self.head[..usize::from(self.shown)]);
        if self.total > usize::from(self.shown) {
            hex.push_str(" …");
        }
        let (name, fields) = match self.packet {
            Some((protocol, id, kind, params)) => {
                let protocol = if protocol == Protocol::Two { "2.0" } else { "1.0" };
                let id = if id == crate::protocol::dynamixel::BROADCAST { "all".to_string() } else { id.to_string() };
                match kind {
                    Kind::Status(error) => (
                        "STATUS".to_string(),
                        format!("ID {id} · {protocol} · error 0x{error:02X} · {}", crate::device::bytes(params)),
                    ),
                    Kind::Instruction(code) => {
                        let name = match code {
                            i::PING => "PING",
                            i::READ => "READ",
                            i::WRITE => "WRITE",
                            i::REG_WRITE => "REG_WRITE",
                            i::ACTION => "ACTION",
                            i::FACTORY_RESET => "FACTORY_RESET",
                            i::REBOOT => "REBOOT",
                            i::SYNC_READ => "SYNC_READ",
                            i::SYNC_WRITE => "SYNC_WRITE",
                            _ => "INSTRUCTION",
                        };
                        (name.to_string(), format!("ID {id} · {protocol} · {}", crate::device::bytes(params)))
                    }
                }
            }
            None => (format!("skipped {}", crate::device::bytes(self.total)), self.why.to_string()),
        };
        crate::device::LogEntry { seconds: self.seconds, direction: self.direction, name, fields, hex }
    }
}
