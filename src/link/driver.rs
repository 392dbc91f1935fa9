//! What the I/O thread drives: a protocol's sans-IO state machine.

use std::time::Instant;

/// A sans-IO state machine the I/O thread can drive. Time is passed in, so a
/// driver is tested by stepping it with fake instants.
pub trait Driver: Send + 'static {
    /// What the owner asks of the driver.
    type Command: Send + 'static;
    /// What the driver reports to the owner.
    type Event: Send + 'static;

    /// A command from the owner.
    fn handle_command(&mut self, now: Instant, command: Self::Command);
    /// Bytes received from the port.
    fn handle_input(&mut self, now: Instant, bytes: &[u8]);
    /// Called when `now` has reached [`Driver::poll_timeout`].
    fn handle_timeout(&mut self, now: Instant);
    /// The link is gone; `reason` says why. Fail whatever is pending.
    fn handle_disconnect(&mut self, reason: &str);
    /// Bytes to write to the port now, if any.
    fn poll_transmit(&mut self, now: Instant) -> Option<Vec<u8>>;
    /// The bytes of the oldest write not yet reported have left: the port's
    /// `write` returned at `now`. A driver that predicts when its bytes arrive
    /// re-bases its predictions on this (a write can leave late: the thread
    /// was descheduled, the port's buffer was full).
    fn handle_written(&mut self, now: Instant, bytes: usize) {
        let _ = (now, bytes);
    }
    /// An event for the owner, if any.
    fn poll_event(&mut self) -> Option<Self::Event>;
    /// When the driver next needs [`Driver::handle_timeout`].
    fn poll_timeout(&self) -> Option<Instant>;
    /// Whether the driver wants the link closed (e.g. an injected disconnect).
    fn wants_close(&self) -> bool {
        false
    }
    /// Whether `command`, still queued when the owner closes the link, is
    /// carried out and written before the link ends (a mobile base's stop
    /// and brake: the owner sent them on its way out). Others are dropped.
    fn is_last_word(&self, command: &Self::Command) -> bool {
        let _ = command;
        false
    }
}
