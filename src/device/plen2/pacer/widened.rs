//! What the adaptive pacing says when it widens its margins or learns a
//! bridge's connection events: why, and the window it allows for from then on.

use std::time::Duration;

use super::RING_WINDOW_BYTES;

/// Why the adaptive pacer widened its margins.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WidenReason {
    /// A reply came in clumps (more bytes at once than a serial line carries)
    /// after gaps this long: the link holds bytes back and delivers them
    /// together (a Bluetooth bridge's connection events, a loaded USB stack).
    Bursts {
        /// The longest gap before a clump.
        gap: Duration,
    },
    /// Replies come slower than the line rate the driver was given: it now
    /// predicts with the measured rate.
    Slow {
        /// The measured rate, bytes a second.
        bytes_per_s: u32,
    },
    /// Replies arrived whole but this late (a bridge that buffers each reply
    /// and hands it over at its next event shows no gap inside one): the
    /// link holds bytes back as long.
    Late {
        /// How late the first byte came, beyond the time its clump needs.
        delay: Duration,
    },
    /// A slot read back different from what was written.
    ReadBackDiffered,
    /// Short getters' round trips agree: the link delivers at connection
    /// events this far apart. No more than a ring's worth an event, none
    /// more after an EEPROM write until it is over even if late by `window`.
    Events {
        /// The connection interval.
        interval: Duration,
    },
}

/// The pacer widened its margins: from now on every byte is assumed to arrive
/// up to `window` late, and no more is in flight than the ring holds then.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Widened {
    /// The longest delivery delay the pacer now allows for.
    pub window: Duration,
    /// What it saw.
    pub reason: WidenReason,
}

impl std::fmt::Display for Widened {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let ms = |d: Duration| d.as_secs_f64() * 1000.0;
        match self.reason {
            WidenReason::Bursts { gap } => write!(
                f,
                "pacing widened: the link delivers in bursts up to {:.1} ms apart; from now on every byte may arrive {:.1} ms late and no more than {RING_WINDOW_BYTES} are in flight",
                ms(gap),
                ms(self.window)
            ),
            WidenReason::Slow { bytes_per_s } => {
                write!(f, "pacing widened: the link carries {bytes_per_s} bytes/s; pacing for that rate from now on")
            }
            WidenReason::Late { delay } => write!(
                f,
                "pacing widened: replies arrive up to {:.1} ms late; from now on every byte may arrive {:.1} ms late and no more than {RING_WINDOW_BYTES} are in flight",
                ms(delay),
                ms(self.window)
            ),
            WidenReason::Events { interval } => write!(
                f,
                "pacing learned the link: it delivers at connection events {:.1} ms apart; from now on no more an event than the robot's ring takes in, and no more than {RING_WINDOW_BYTES} bytes after an EEPROM write until it is over, even if the write came {:.1} ms late",
                ms(interval),
                ms(self.window)
            ),
            WidenReason::ReadBackDiffered => write!(
                f,
                "pacing widened: a slot read back different; from now on every byte may arrive {:.1} ms late and no more than {RING_WINDOW_BYTES} are in flight",
                ms(self.window)
            ),
        }
    }
}
