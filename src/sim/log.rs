//! `sim --log FILE`: every command an emulated board receives, a line each,
//! with the system's monotonic clock in nanoseconds when the board took it
//! in (its last byte in, or — behind an emulated Bluetooth bridge — when the
//! bridge delivered it) — comparable between processes, so several boards'
//! logs line up (for users debugging a show's timing, and for tests).

use std::fs::File;
use std::io::{BufWriter, Write};
use std::time::Instant;

use super::{Plen2SimEvent, RflexSimEvent, SimEvent};
use crate::link::Driver;

/// An emulator's event that says a command was received, in words.
pub trait Received {
    /// The command, as the log writes it, when the event is one.
    fn received(&self) -> Option<String>;
}

impl Received for SimEvent {
    fn received(&self) -> Option<String> {
        match self {
            Self::Handled(message) => Some(format!("{message:?}")),
            Self::MacroSteps { .. } => None,
        }
    }
}

impl Received for Plen2SimEvent {
    fn received(&self) -> Option<String> {
        match self {
            Self::Executed(command) => Some(command.to_ascii()),
            Self::Dropped(error) => Some(format!("dropped: {error}")),
            Self::Lost(bytes) => Some(format!("lost: {bytes} bytes (the ring was full)")),
            Self::Cycle(_) | Self::MotionStarted { .. } => None,
        }
    }
}

impl Received for RflexSimEvent {
    fn received(&self) -> Option<String> {
        match self {
            Self::Received(command) => Some(format!("{command:?}")),
            Self::DeadManStop => Some("dead-man stop (no command in time)".into()),
        }
    }
}

/// The system's monotonic clock, ns, for an [`Instant`] (which is that clock on Linux and macOS).
#[derive(Clone, Copy, Debug)]
pub struct MonotonicClock {
    at: Instant,
    ns: u128,
}

impl MonotonicClock {
    /// The clock read now, beside [`Instant::now`]: read on both sides of it,
    /// the tightest of a few tries kept and its middle taken, so that a
    /// thread preempted between two reads (a busy machine) does not shift
    /// every time it converts.
    pub fn now() -> Self {
        let mut best: Option<(u128, Self)> = None;
        for _ in 0..5 {
            let before = monotonic_ns();
            let at = Instant::now();
            let after = monotonic_ns();
            let gap = after.saturating_sub(before);
            if best.as_ref().is_none_or(|(known, _)| gap < *known) {
                best = Some((gap, Self { at, ns: before + gap / 2 }));
            }
        }
        best.map_or_else(|| Self { at: Instant::now(), ns: monotonic_ns() }, |(_, clock)| clock)
    }

    /// `instant` on the system's monotonic clock, ns.
    pub fn ns(&self, instant: Instant) -> u128 {
        match instant.checked_duration_since(self.at) {
            Some(after) => self.ns + after.as_nanos(),
            None => self.ns.saturating_sub(self.at.duration_since(instant).as_nanos()),
        }
    }
}

#[cfg(unix)]
fn monotonic_ns() -> u128 {
    let now = rustix::time::clock_gettime(rustix::time::ClockId::Monotonic);
    u128::try_from(now.tv_sec).unwrap_or(0) * 1_000_000_000 + u128::try_from(now.tv_nsec).unwrap_or(0)
}

#[cfg(not(unix))]
fn monotonic_ns() -> u128 {
    // No shared monotonic clock to read: time from the log's start.
    0
}

/// An emulator that also writes what it receives to a log.
pub struct Logged<D> {
    inner: D,
    log: BufWriter<File>,
    clock: MonotonicClock,
    /// When the board last ran (bytes in, or a timer).
    last_input: Instant,
}

impl<D> Logged<D> {
    /// `inner`, logging to `log`.
    pub fn new(inner: D, log: File) -> Self {
        let clock = MonotonicClock::now();
        Self { inner, log: BufWriter::new(log), clock, last_input: clock.at }
    }
}

impl<D: Driver> Driver for Logged<D>
where
    D::Event: Received,
{
    type Command = D::Command;
    type Event = D::Event;

    fn handle_command(&mut self, now: Instant, command: Self::Command) {
        self.inner.handle_command(now, command);
    }

    fn handle_input(&mut self, now: Instant, bytes: &[u8]) {
        self.last_input = now;
        self.inner.handle_input(now, bytes);
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.last_input = now;
        self.inner.handle_timeout(now);
    }

    fn handle_disconnect(&mut self, reason: &str) {
        let _ = writeln!(self.log, "{} disconnected: {reason}", self.clock.ns(Instant::now()));
        let _ = self.log.flush();
        self.inner.handle_disconnect(reason);
    }

    fn poll_transmit(&mut self, now: Instant) -> Option<Vec<u8>> {
        self.inner.poll_transmit(now)
    }

    fn handle_written(&mut self, now: Instant, bytes: usize) {
        self.inner.handle_written(now, bytes);
    }

    fn poll_event(&mut self) -> Option<Self::Event> {
        let event = self.inner.poll_event()?;
        if let Some(said) = event.received() {
            // A log that cannot be written must not stop the board: the line is lost.
            let _ = writeln!(self.log, "{} {said}", self.clock.ns(self.last_input));
            let _ = self.log.flush();
        }
        Some(event)
    }

    fn poll_timeout(&self) -> Option<Instant> {
        self.inner.poll_timeout()
    }

    fn wants_close(&self) -> bool {
        self.inner.wants_close()
    }

    fn is_last_word(&self, command: &Self::Command) -> bool {
        self.inner.is_last_word(command)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use std::time::Duration;

    #[test]
    fn instants_map_onto_the_system_clock_in_order() {
        let clock = MonotonicClock::now();
        let later = clock.at + Duration::from_millis(5);
        assert_eq!(clock.ns(later) - clock.ns(clock.at), 5_000_000);
        let earlier = clock.at.checked_sub(Duration::from_millis(2)).unwrap();
        assert_eq!(clock.ns(clock.at) - clock.ns(earlier), 2_000_000);
        let again = MonotonicClock::now();
        assert!(again.ns >= clock.ns, "the system clock does not go back");
    }
}
