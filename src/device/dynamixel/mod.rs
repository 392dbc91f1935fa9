//! The DYNAMIXEL family's driver: the driver the I/O thread runs
//! ([`DynamixelDriver`], sans IO) and the handle the editor and the command
//! line hold ([`DynamixelBus`]): a scan of both protocols, each servo found
//! with its model, firmware and limits, goals coalesced into sync writes,
//! torque, LED and profile written, and each servo read 50 times a second
//! (position, load, voltage, temperature, hardware errors); a servo that
//! stops answering is said silent. A DYNAMIXEL stores no motion: what it
//! plays is streamed from the computer as goals.

mod doctor;
mod driver;
mod fields;
mod logged;
mod stream;
#[cfg(test)]
mod tests;

use std::ops::RangeInclusive;
use std::time::Instant;

pub use doctor::Said;
pub use driver::{ANSWER_WAIT, DynamixelDriver, READ_EVERY, SILENT_AFTER, SILENT_AFTER_MISSES};
pub use logged::Logged;

use crate::link::{self, Connection, LinkEvent, LinkHandle, Waker};
use crate::project::Family;
pub use crate::protocol::dynamixel::Protocol;
pub use crate::protocol::dynamixel::table::{Known, known};

inventory::submit! {
    crate::device::family::Registered {
        family: Family::Dynamixel,
        // The X-series' factory line rate (an AX leaves the factory at 1 Mbps).
        line: || link::LineSettings::new(57_600),
        // After the families that answer at their own rates: a ping is harmless to them all.
        doctor: Some(crate::device::family::Doctor { rank: 3, recogniser: doctor::recogniser }),
    }
}
inventory::submit! {
    // An AX leaves the factory at 1 Mbps; 115200 is the other rate Bioloid kits ship at.
    crate::device::family::MoreRates { family: Family::Dynamixel, rates: &[1_000_000, 115_200] }
}

/// The IDs a scan pings one by one in Protocol 1.0 (2.0 is pinged by broadcast).
pub const ONE_IDS: RangeInclusive<u8> = 0..=252;

/// A servo a scan found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Found {
    /// Its ID.
    pub id: u8,
    /// The protocol it answered in.
    pub protocol: Protocol,
    /// Its model number (what its control table starts with).
    pub model_number: u16,
    /// Its firmware version.
    pub firmware: u8,
}

impl Found {
    /// Its model, if the driver knows its table.
    pub fn model(&self) -> Option<&'static Known> {
        known(self.model_number)
    }

    /// Its model's name, or its number where the model is not known.
    pub fn model_name(&self) -> String {
        self.model().map_or_else(|| format!("model {}", self.model_number), |model| model.name.to_string())
    }
}

/// A servo's limits, read from its own control table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Its lowest position (X: Min Position Limit; AX: CW Angle Limit).
    pub lowest: u32,
    /// Its highest position (X: Max Position Limit; AX: CCW Angle Limit).
    pub highest: u32,
    /// Its temperature limit, °C.
    pub temperature_limit_c: u8,
}

/// What a servo said of itself in a round of readings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reading {
    /// Its present position, in its own units.
    pub position: u32,
    /// Its present load, % of its most (negative: clockwise).
    pub load_percent: f64,
    /// Its input voltage, volts.
    pub volts: f64,
    /// Its temperature, °C.
    pub temperature_c: u8,
    /// Its hardware errors (the bits of Hardware Error Status, or of 1.0's error byte): 0 for none.
    pub hardware_error: u8,
    /// When it came.
    pub at: Instant,
}

/// A hardware error's bits, named as the e-Manual names them.
pub const HARDWARE_ERRORS: [(u8, &str); 5] = [
    (0x01, "input voltage"),
    (0x04, "overheating"),
    (0x08, "motor encoder"),
    (0x10, "electrical shock"),
    (0x20, "overload"),
];

/// What the owner asks of the bus.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DynamixelCommand {
    /// Finds the servos: 2.0 by broadcast ping, then these IDs one by one in 1.0.
    Scan {
        /// The 1.0 IDs to ping.
        one: RangeInclusive<u8>,
    },
    /// Servo `id` to `position` (its own units); only the newest of each servo goes.
    Goal {
        /// The servo.
        id: u8,
        /// Where to, in its units.
        position: u32,
    },
    /// Torque on or off, for servo `id` or (none) for every servo found.
    Torque {
        /// The servo, or every one.
        id: Option<u8>,
        /// On or off.
        on: bool,
    },
    /// Servo `id`'s LED on or off.
    Led {
        /// The servo.
        id: u8,
        /// Lit or not.
        on: bool,
    },
    /// Servo `id`'s profile: velocity and acceleration (its units; 0 is as fast as it can).
    Profile {
        /// The servo.
        id: u8,
        /// Profile velocity (AX: moving speed).
        velocity: u32,
        /// Profile acceleration (none on the AX).
        acceleration: u32,
    },
    /// Plays `frames` from now, one every `every` (a sync write of each
    /// frame's goals on its own clock, whatever the editor draws); a frame
    /// that falls due late goes as the newest due, never bunched.
    Stream {
        /// Each frame: the servos' goals.
        frames: Vec<Vec<(u8, u32)>>,
        /// The time between two frames.
        every: std::time::Duration,
    },
    /// Pings servo `id` (its answer is [`DynamixelEvent::Pong`]): a link's round trip.
    Ping {
        /// The servo.
        id: u8,
        /// In its protocol.
        protocol: Protocol,
    },
    /// Whether the servos are read 50 times a second.
    Read(bool),
    /// STOP: what streams ends, and every servo is held where it last said it is.
    Hold,
}

/// What the bus said.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DynamixelEvent {
    /// A packet went out or came in, for the packet log.
    Logged(Logged),
    /// A scan pinged `done` of `of` Protocol 1.0 IDs.
    Scanning {
        /// How many.
        done: usize,
        /// Of how many.
        of: usize,
    },
    /// A servo answered.
    Found(Found),
    /// The scan is over.
    Scanned {
        /// How many servos it found.
        found: usize,
    },
    /// Servo `id`'s limits.
    Limits {
        /// The servo.
        id: u8,
        /// Its limits.
        limits: Limits,
    },
    /// Servo `id` said where it is and how it fares.
    Reading {
        /// The servo.
        id: u8,
        /// What it said.
        reading: Reading,
    },
    /// Servo `id` refused a write (its status's error byte).
    Refused {
        /// The servo.
        id: u8,
        /// What was written.
        what: &'static str,
        /// Its error byte.
        error: u8,
    },
    /// A stream's last frame went out.
    Streamed,
    /// Servo `id` answered a [`DynamixelCommand::Ping`].
    Pong {
        /// The servo.
        id: u8,
    },
    /// Servo `id` stopped answering.
    Silent {
        /// The servo.
        id: u8,
    },
    /// Servo `id` answers again.
    Answering {
        /// The servo.
        id: u8,
    },
}

/// A connected DYNAMIXEL bus.
#[derive(Debug)]
pub struct DynamixelHandle {
    link: LinkHandle<DynamixelCommand, DynamixelEvent>,
}

impl DynamixelHandle {
    /// Starts the I/O thread over an opened connection.
    pub fn over(connection: Connection, waker: Waker) -> std::io::Result<Self> {
        Ok(Self { link: link::spawn(connection, DynamixelDriver::default(), waker)? })
    }

    /// Asks the bus (a closed link is said by `events`).
    pub fn send(&self, command: DynamixelCommand) {
        let _ = self.link.commands().send(command);
    }

    /// What the bus said, and the link's end.
    pub fn events(&self) -> &crossbeam_channel::Receiver<LinkEvent<DynamixelEvent>> {
        self.link.events()
    }
}

impl Drop for DynamixelHandle {
    /// A bus let go holds its servos where they are (never left running toward a goal).
    fn drop(&mut self) {
        self.send(DynamixelCommand::Hold);
    }
}
