//! What the editor knows of the bus: each servo found, its limits, its last
//! reading and what the editor asked of it; a servo's units and degrees; a
//! motion sampled into the frames streamed to the servos.

use std::collections::BTreeMap;
use std::time::Duration;

use crate::device::dynamixel::{Found, Limits, Reading};
use crate::project::dynamixel::Motion;
pub use crate::project::dynamixel::{degrees, units};

/// The time between two streamed frames (50 a second, as the servos are read).
pub const FRAME: Duration = Duration::from_millis(20);

/// The servos on the bus.
#[derive(Debug, Default)]
pub struct Bus {
    /// Each servo found, by ID.
    pub servos: BTreeMap<u8, BusServo>,
    /// A scan under way: 1.0 IDs pinged, of how many.
    pub scanning: Option<(usize, usize)>,
}

impl Bus {
    /// Where each servo last said it is, by ID.
    pub fn present(&self) -> BTreeMap<u8, u32> {
        self.servos.values().filter_map(|servo| Some((servo.found.id, servo.reading?.position))).collect()
    }
}

/// One servo found on the bus.
#[derive(Clone, Debug)]
pub struct BusServo {
    /// What the scan found.
    pub found: Found,
    /// Its limits, once read.
    pub limits: Option<Limits>,
    /// What it said last.
    pub reading: Option<Reading>,
    /// Where the editor sent it last (none: where it is).
    pub goal: Option<u32>,
    /// Whether its torque is on, as the editor set it.
    pub torque: bool,
    /// Whether its LED is lit, as the editor set it.
    pub led: bool,
    /// Whether it stopped answering.
    pub silent: bool,
}

impl BusServo {
    /// A servo just found.
    pub fn new(found: Found) -> Self {
        Self { found, limits: None, reading: None, goal: None, torque: false, led: false, silent: false }
    }

    /// Its range: its limits, else its model's whole table.
    pub fn range(&self) -> (u32, u32) {
        let top = self.found.model().map_or(4095, |model| model.layout.top_position);
        self.limits.map_or((0, top), |limits| (limits.lowest.min(top), limits.highest.min(top)))
    }

    /// `position` within its limits: a servo never slams into its stops.
    pub fn clamp(&self, position: u32) -> u32 {
        let (lowest, highest) = self.range();
        position.clamp(lowest, highest.max(lowest))
    }

    /// Where its slider stands: where the editor sent it, else where it is.
    pub fn shown(&self) -> Option<u32> {
        self.goal.or(self.reading.map(|reading| reading.position))
    }
}

/// `motion` sampled every [`FRAME`] from where the servos are, each position
/// within its servo's limits: what is streamed, the same poses the plot draws.
pub fn frames(motion: &Motion, bus: &Bus) -> Vec<Vec<(u8, u32)>> {
    let every_ms = FRAME.as_secs_f64() * 1000.0;
    motion
        .frames(&bus.present(), every_ms)
        .into_iter()
        .map(|pose| {
            pose.into_iter()
                .filter_map(|(id, position)| bus.servos.get(&id).map(|servo| (id, servo.clamp(position))))
                .collect()
        })
        .collect()
}
