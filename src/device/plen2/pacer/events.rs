//! The adaptive pacing on a link that delivers at connection events (a
//! Bluetooth LE bridge): what reaches the robot comes in bunches, one an
//! event, of what reached the bridge since the event before. Two rules keep
//! the robot's 64-byte ring from overflowing, whatever the events' phase:
//! - **a bunch fits the ring**: no more handed out within one interval (and a
//!   margin) than the ring holds while the firmware reads it as it comes in
//!   (see [`Events::bunch`]), so no event carries more;
//! - **an EEPROM wait is never overrun**: after a command that makes the
//!   firmware write its EEPROM, no more than [`RING_WINDOW_BYTES`] until the
//!   write is over even if the command reached the robot as late as the link
//!   has shown it may — or, when the write ends before the next event, until
//!   the command's own event has surely gone by (what follows rides a later one).
//!
//! The interval is learned from round trips of short getters each sent the
//! moment the reply before it ended (just after an event): the getter rides
//! the next event and its answer the one after, two intervals, whatever the
//! phases — bytes wait for the *next* event, the bridge's description says,
//! and the one that brought the reply has closed by the time the host has
//! taken it in and written again. How late a byte may reach the robot is a reply's round trip less
//! the interval its answer waited, over the last few replies: one reply held
//! up by a busy host widens it for a while, not for the session.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use super::RING_WINDOW_BYTES;

/// A reply this short is a round trip's sample (`<VI`'s answer: about 80 bytes).
const SAMPLE_REPLY_BYTES: usize = 256;
/// Round trips agreeing within this (or a tenth of theirs) show events.
const AGREEMENT: Duration = Duration::from_millis(1);
/// The shortest connection interval (Bluetooth LE: 7.5 ms), less a margin:
/// round trips shorter than twice this are a line's, not a bridge's.
const SHORTEST_INTERVAL: Duration = Duration::from_millis(5);
/// Short getters asked before deciding there are no events to learn: one at
/// any time, then back to back until two agree — a few more when a busy
/// host blurs them.
pub const ROUND_TRIPS: usize = 6;
/// Host → robot bytes a Bluetooth LE bridge carries in one connection event.
const BRIDGE_EVENT_BYTES: usize = 80;
/// Replies whose lateness the pacing keeps in mind.
const REMEMBERED: usize = 4;

/// What a getter's round trip can tell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sample {
    /// Sent the moment the reply before ended (just after an event): it
    /// rides the next event — bytes wait for the next one, the bridge's
    /// description says: one under way has closed by the time the host has
    /// taken in a reply and written again — and its answer the one after.
    BackToBack,
    /// Anything else.
    Other,
}

/// Whether two round trips agree (within 1 ms or a tenth).
fn agree(one: Duration, other: Duration) -> bool {
    one.abs_diff(other) <= AGREEMENT.max(one.max(other) / 10)
}

/// The event-link state (see the module documentation).
#[derive(Debug, Default)]
pub struct Events {
    /// Round trips of short getters sent the moment the reply before ended.
    round_trips: Vec<Duration>,
    /// Short replies seen while learning (the probe asks no more than a few).
    asked: usize,
    /// The connection interval, once the round trips agreed.
    interval: Option<Duration>,
    /// How late each of the last replies showed a byte may reach the robot.
    recent: VecDeque<Duration>,
    /// When each byte handed out within the last span was.
    handed: VecDeque<Instant>,
    /// EEPROM waits not over at their latest: (bytes handed out up to and
    /// including the command's last, when the wait is over at the latest).
    waits: VecDeque<(u64, Instant)>,
    /// Bytes handed out in all.
    placed: u64,
}

impl Events {
    /// The connection interval, once learned.
    pub fn interval(&self) -> Option<Duration> {
        self.interval
    }

    /// Whether another round trip would still teach something.
    pub fn wants_round_trips(&self) -> bool {
        self.interval.is_none() && self.asked <= ROUND_TRIPS
    }

    /// What a getter handed out at `sent` is a sample of.
    pub fn sample(reply_ended: Option<Instant>, sent: Instant) -> Sample {
        if reply_ended == Some(sent) { Sample::BackToBack } else { Sample::Other }
    }

    /// A reply of `bytes` to a getter (a `sample`) sent at `sent` began
    /// arriving at `first`, its first bytes needing `own` to be printed.
    /// Returns the interval when this reply taught it.
    pub fn reply(
        &mut self,
        sample: Sample,
        (sent, first): (Instant, Instant),
        own: Duration,
        bytes: usize,
    ) -> Option<Duration> {
        let round_trip = first.saturating_duration_since(sent);
        if let Some(interval) = self.interval {
            // The answer waited an interval for its event (after it was
            // printed); the rest is the getter's way there.
            self.recent.push_back(round_trip.saturating_sub(interval + own));
            if self.recent.len() > REMEMBERED {
                self.recent.pop_front();
            }
            return None;
        }
        if bytes > SAMPLE_REPLY_BYTES {
            return None;
        }
        self.asked += 1;
        match sample {
            Sample::BackToBack if round_trip < SHORTEST_INTERVAL * 2 => {
                // A line's round trip, not a bridge's: nothing more to learn here.
                self.asked = ROUND_TRIPS + 1;
                None
            }
            Sample::BackToBack => {
                self.round_trips.push(round_trip);
                // Two events a round trip.
                let interval = self.typical()? / 2;
                self.interval = Some(interval);
                self.recent.push_back(interval);
                Some(interval)
            }
            Sample::Other => None,
        }
    }

    /// The back-to-back round trip most of them agree on, once another agrees
    /// with the median: the longest of those that agree with it. A busy host
    /// blurs round trips either way — a reply taken in late makes the getter
    /// after it look quicker — and an interval taken too short could let two
    /// bunches into one event, one taken too long only paces more slowly.
    fn typical(&self) -> Option<Duration> {
        let mut sorted = self.round_trips.clone();
        sorted.sort();
        let median = *sorted.get(sorted.len() / 2)?;
        let agreeing: Vec<Duration> = sorted.into_iter().filter(|round_trip| agree(*round_trip, median)).collect();
        (agreeing.len() >= 2).then(|| agreeing.into_iter().max()).flatten()
    }

    /// The longest a byte may take to reach the robot, from what the link
    /// showed lately: at least an interval (it waits for the next event).
    pub fn robot_late(&self) -> Option<Duration> {
        let interval = self.interval?;
        Some(self.recent.iter().copied().fold(interval, Duration::max))
    }

    /// A longer gap than one interval between a reply's events: an event went
    /// by without it, and bytes to the robot may wait as long.
    pub fn gap(&mut self, gap: Duration) {
        if self.interval.is_some_and(|interval| gap > interval + interval / 2) {
            self.recent.push_back(gap);
            if self.recent.len() > REMEMBERED {
                self.recent.pop_front();
            }
        }
    }

    /// The span within which at most a bunch is handed out: an interval, and
    /// a margin for the host's own lateness.
    fn span(interval: Duration) -> Duration {
        interval + Duration::from_millis(3)
    }

    /// The most one event may carry: what leaves [`RING_WINDOW_BYTES`] in
    /// the ring at its fullest when the bytes come in a `line_byte` apart and
    /// the firmware reads one every `byte_read` — and no more than a bridge
    /// carries in an event (80), so none spills into the next.
    pub fn bunch(line_byte: Duration, byte_read: Duration) -> usize {
        let kept = 1.0 - (line_byte.as_secs_f64() / byte_read.as_secs_f64()).min(1.0);
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, clippy::cast_precision_loss)]
        let bunch = (RING_WINDOW_BYTES as f64 / kept.max(f64::EPSILON)).floor() as usize;
        bunch.clamp(RING_WINDOW_BYTES, BRIDGE_EVENT_BYTES)
    }

    fn settle(&mut self, now: Instant, interval: Duration) {
        let span = Self::span(interval);
        while self.handed.front().is_some_and(|at| *at + span <= now) {
            self.handed.pop_front();
        }
        while self.waits.front().is_some_and(|(_, end)| *end <= now) {
            self.waits.pop_front();
        }
    }

    /// Bytes that may be handed out now, by both rules, `bunch` an event.
    pub fn room(&mut self, now: Instant, bunch: usize) -> usize {
        let Some(interval) = self.interval else { return RING_WINDOW_BYTES };
        self.settle(now, interval);
        let bunch = bunch.saturating_sub(self.handed.len());
        let after_wait = self.waits.front().map_or(0, |(placed, _)| self.placed - placed);
        bunch.min(RING_WINDOW_BYTES.saturating_sub(usize::try_from(after_wait).unwrap_or(usize::MAX)))
    }

    /// When both rules next allow a byte, from `now`, `bunch` an event.
    pub fn next_room(&self, now: Instant, bunch: usize) -> Instant {
        let Some(interval) = self.interval else { return now };
        let span = Self::span(interval);
        let live: Vec<Instant> = self.handed.iter().copied().filter(|at| *at + span > now).collect();
        let bunch = live.len().checked_sub(bunch).map_or(now, |index| live[index] + span);
        // The first wait with room after it; until the one before it is over.
        let limit = RING_WINDOW_BYTES as u64;
        let mut after_wait = now;
        for (placed, end) in self.waits.iter().filter(|(_, end)| *end > now) {
            if self.placed - placed < limit {
                break;
            }
            after_wait = *end;
        }
        bunch.max(after_wait).max(now)
    }

    /// A byte was handed out at `now`; `wait_over`, when it ends a command
    /// that makes the firmware wait: when that wait is over at the latest.
    pub fn place(&mut self, now: Instant, wait_over: Option<Instant>) {
        if self.interval.is_none() {
            return;
        }
        self.handed.push_back(now);
        self.placed += 1;
        if let Some(end) = wait_over {
            self.waits.push_back((self.placed, end));
        }
    }

    /// A write planned at `planned` left `delay` late: what was handed out
    /// with it and after left as much later.
    pub fn shift(&mut self, planned: Instant, delay: Duration) {
        for at in self.handed.iter_mut().chain(self.waits.iter_mut().map(|(_, end)| end)) {
            if *at >= planned {
                *at += delay;
            }
        }
    }

    /// The link ended: nothing is in flight.
    pub fn reset(&mut self) {
        self.handed.clear();
        self.waits.clear();
    }
}
