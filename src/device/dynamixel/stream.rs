//! A motion being streamed: its frames, each due at its own time from the
//! start, and the newest due taken (a frame that falls due late is skipped
//! for a later one, never sent bunched).

use std::time::{Duration, Instant};

/// A stream being played.
#[derive(Clone, Debug)]
pub(super) struct Stream {
    frames: Vec<Vec<(u8, u32)>>,
    every: Duration,
    start: Instant,
    /// The next frame to send.
    next: usize,
}

impl Stream {
    /// `frames`, one every `every` from `start`.
    pub(super) fn new(frames: Vec<Vec<(u8, u32)>>, every: Duration, start: Instant) -> Self {
        Self { frames, every, start, next: 0 }
    }

    /// When frame `index` is due.
    fn due(&self, index: usize) -> Instant {
        self.start + self.every * u32::try_from(index).unwrap_or(u32::MAX)
    }

    /// When the next frame is due.
    pub(super) fn next_due(&self) -> Instant {
        self.due(self.next)
    }

    /// The newest frame due by `now`, and whether it was the last.
    pub(super) fn take_due(&mut self, now: Instant) -> Option<(Vec<(u8, u32)>, bool)> {
        let mut due = None;
        while self.next < self.frames.len() && self.due(self.next) <= now {
            due = Some(self.next);
            self.next += 1;
        }
        let index = due?;
        Some((std::mem::take(&mut self.frames[index]), self.next == self.frames.len()))
    }
}
