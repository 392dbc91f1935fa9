//! When the PLEN2 driver may hand bytes to the port. The robot acknowledges
//! nothing and loses what overflows its 64-byte ring, so the pacer predicts
//! when the firmware reads each byte (its line, its read rate, its EEPROM
//! waits), re-bases every prediction on when a write really left, and — in
//! the adaptive mode — learns from replies how late or bursty the link is and
//! widens its margins for the rest of the session. Sans-IO: time comes in.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

pub use super::link_report::{CLUMP_GAP, LinkReport};

mod events;
mod widened;

use events::Events;
pub use widened::{WidenReason, Widened};

/// The firmware timing the pacer assumes: plen2.md's figures at the slow end of their ranges.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pacing {
    /// Time the firmware takes to read one byte.
    pub byte_read: Duration,
    /// EEPROM write after a `>MH`.
    pub header_write: Duration,
    /// EEPROM write after a `>MF`.
    pub frame_write: Duration,
    /// EEPROM write after a `>HO` / `>MA` / `>MI`.
    pub joint_write: Duration,
    /// `>JS`.
    pub factory_reset: Duration,
    /// Bytes allowed to wait in the robot's 64-byte ring (the rest is slack for
    /// delivery jitter: a late batch arrives together with the next).
    pub ring_budget: u32,
}

impl Default for Pacing {
    fn default() -> Self {
        Self {
            // plen2.md §5: "about 20 µs"; 5 % more.
            byte_read: Duration::from_micros(21),
            // The top of each range plen2.md gives: 5–6 ms, 10–12 ms, 3–7 ms, about 0.5 s.
            header_write: Duration::from_millis(6),
            frame_write: Duration::from_millis(12),
            joint_write: Duration::from_millis(7),
            factory_reset: Duration::from_millis(600),
            ring_budget: 24,
        }
    }
}

/// How the driver paces an upload.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum PacingMode {
    /// As fast as the firmware reads, from its own timing (the ring refilled
    /// in whole batches once predicted empty); never widens.
    Fast,
    /// Starts fast; widens its margins when replies show the link is late or
    /// bursty, or a read-back differs.
    #[default]
    Adaptive,
    /// The official tool's pacing: 32 bytes, then 50 ms, whatever the link.
    Safe,
}

impl PacingMode {
    /// Every mode, in the order a picker offers them.
    pub const ALL: [Self; 3] = [Self::Fast, Self::Adaptive, Self::Safe];

    /// The command line's word for it.
    pub fn word(self) -> &'static str {
        match self {
            Self::Fast => "fast",
            Self::Adaptive => "adaptive",
            Self::Safe => "safe",
        }
    }
}

impl std::str::FromStr for PacingMode {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|mode| mode.word() == text.trim().to_ascii_lowercase())
            .ok_or_else(|| format!("{text:?} is not a pacing: use fast, adaptive or safe"))
    }
}

/// Bytes the widened pacer lets be in flight, not yet read by the firmware
/// even if each arrived as late as the window allows (the rest of the
/// 64-byte ring is slack for a STOP).
pub const RING_WINDOW_BYTES: usize = 56;
/// The official tool's pacing: this many bytes…
pub const SAFE_BURST: usize = 32;
/// …then this long.
pub const SAFE_PAUSE: Duration = Duration::from_millis(50);
/// More bytes than this arriving at once is a clump: two USB packets.
pub const CLUMP_BYTES: usize = 128;
/// A reply this long tells the line's rate.
const RATE_SAMPLE_BYTES: usize = 1024;
/// The window a read-back difference widens to when nothing else was seen.
pub const DIFFERENCE_WINDOW: Duration = Duration::from_millis(25);
/// The fastest the robot prints a reply: a byte a microsecond (USB full speed).
const FASTEST_REPLY_BYTE: Duration = Duration::from_micros(1);
/// The widest window: beyond it the link is not a serial line any more.
pub const MAX_WINDOW: Duration = Duration::from_millis(200);

/// One reply being watched: how it arrived.
#[derive(Debug)]
struct Watched {
    /// When the robot should have begun printing it (the getter read).
    expected: Instant,
    /// When the getter was handed out, and what its round trip samples.
    sent: Instant,
    sample: events::Sample,
    first: Option<Instant>,
    last: Option<Instant>,
    /// Bytes after the first arrival (for the rate).
    later_bytes: usize,
    /// Bytes of the first arrival.
    first_bytes: usize,
    /// The clump arriving now: its bytes and the gap before it.
    clump: (usize, Duration),
    /// The longest gap before a clump.
    max_gap: Duration,
}

impl Watched {
    fn close_clump(&mut self) {
        let (bytes, gap) = self.clump;
        if bytes > CLUMP_BYTES && gap > CLUMP_GAP {
            self.max_gap = self.max_gap.max(gap);
        }
    }
}

/// The pacer's state (see the module documentation).
#[derive(Debug)]
pub struct Pacer {
    mode: PacingMode,
    timing: Pacing,
    line_byte: Duration,
    /// The robot's own line, as given: the fastest its bytes can come in
    /// (what a slower reply shows is the link's way back, not this).
    robot_byte: Duration,
    /// Predicted read time of each byte sent and not yet read.
    in_ring: VecDeque<Instant>,
    /// When the firmware reads the next byte sent (EEPROM waits included).
    next_read: Option<Instant>,
    /// When the line has carried everything sent.
    line_free: Option<Instant>,
    /// Writes handed out whose leaving is not yet reported: (planned, bytes).
    unconfirmed: VecDeque<(Instant, usize)>,
    /// Widened: how late any byte may arrive (predictions assume that late).
    window: Option<Duration>,
    /// Safe: when the next burst may go, and bytes left in this one.
    safe_open_at: Option<Instant>,
    safe_left: usize,
    watched: Option<Watched>,
    /// A reply long enough to show the link has been watched.
    measured: bool,
    report: LinkReport,
    widened: VecDeque<Widened>,
    /// A link that delivers at connection events.
    events: Events,
    /// When the last reply ended (a getter handed out then is back to back).
    reply_ended_at: Option<Instant>,
}

impl Pacer {
    /// A pacer for a robot with `timing`, on a line of `line_baud`.
    pub fn new(mode: PacingMode, timing: Pacing, line_baud: u32) -> Self {
        Self {
            mode,
            timing,
            line_byte: Duration::from_secs_f64(10.0 / f64::from(line_baud.max(1))),
            robot_byte: Duration::from_secs_f64(10.0 / f64::from(line_baud.max(1))),
            in_ring: VecDeque::new(),
            next_read: None,
            line_free: None,
            unconfirmed: VecDeque::new(),
            window: None,
            safe_open_at: None,
            safe_left: SAFE_BURST,
            watched: None,
            measured: false,
            report: LinkReport::default(),
            widened: VecDeque::new(),
            events: Events::default(),
            reply_ended_at: None,
        }
    }

    /// The mode.
    pub fn mode(&self) -> PacingMode {
        self.mode
    }

    /// Whether the pacer still has to see a reply before it knows the link
    /// (only the adaptive pacing learns).
    pub fn wants_measurement(&self) -> bool {
        self.mode == PacingMode::Adaptive && (!self.measured || self.events.wants_round_trips())
    }

    /// Whether the probe should time another short getter's round trip
    /// (the adaptive pacing learns a bridge's connection events from them).
    pub fn wants_round_trip(&self) -> bool {
        self.mode == PacingMode::Adaptive && self.events.wants_round_trips()
    }

    /// The connection interval of a link that delivers at events, once learned.
    pub fn interval(&self) -> Option<Duration> {
        self.events.interval()
    }

    /// Whether the event rules pace (adaptive, the link's events learned).
    fn by_events(&self) -> bool {
        self.mode == PacingMode::Adaptive && self.events.interval().is_some()
    }

    /// What the replies so far showed of the link.
    pub fn report(&self) -> LinkReport {
        self.report
    }

    /// The window the pacer allows for, once widened.
    pub fn window(&self) -> Option<Duration> {
        self.window
    }

    /// When the firmware is predicted to have read everything sent so far.
    pub fn firmware_free(&self) -> Option<Instant> {
        self.next_read
    }

    /// Forgets what the firmware has read by `now`.
    fn settle(&mut self, now: Instant) {
        while self.in_ring.front().is_some_and(|read| *read <= now) {
            self.in_ring.pop_front();
        }
    }

    /// How many bytes may be handed to the port now. `urgent` (STOP) skips
    /// the official pause, never the ring.
    pub fn room(&mut self, now: Instant, urgent: bool) -> usize {
        self.settle(now);
        if self.mode == PacingMode::Safe && !urgent {
            return if self.safe_open_at.is_none_or(|open| now >= open) { self.safe_left } else { 0 };
        }
        if self.by_events() {
            return self.events.room(now, Events::bunch(self.robot_byte, self.timing.byte_read));
        }
        if self.window.is_some() {
            // Widened: every byte predicted as if it arrived as late as the
            // window allows; what it then predicts unread must fit the ring.
            return RING_WINDOW_BYTES.saturating_sub(self.in_ring.len());
        }
        // Refill in whole batches, once the ring is predicted empty: a batch
        // delivered late together with the next still fits (the slack).
        if self.in_ring.is_empty() { self.timing.ring_budget as usize } else { 0 }
    }

    /// When [`Pacer::room`] is next above zero, from `now`.
    pub fn next_room(&self, now: Instant) -> Instant {
        if self.mode == PacingMode::Safe {
            return self.safe_open_at.map_or(now, |open| open.max(now));
        }
        if self.by_events() {
            return self.events.next_room(now, Events::bunch(self.robot_byte, self.timing.byte_read));
        }
        let at = if self.window.is_some() {
            // Room for one byte once all but RING_WINDOW_BYTES − 1 are read.
            let must_read = (self.in_ring.len() + 1).saturating_sub(RING_WINDOW_BYTES);
            must_read.checked_sub(1).and_then(|index| self.in_ring.get(index).copied())
        } else {
            self.in_ring.back().copied()
        };
        at.map_or(now, |at| at.max(now))
    }

    /// A byte handed out at `now`; `busy` is the EEPROM wait when it ends a
    /// command. Returns when the firmware is predicted to have read it.
    pub fn place(&mut self, now: Instant, busy: Duration) -> Instant {
        let arrives = self.line_free.map_or(now, |free| free.max(now)) + self.line_byte;
        self.line_free = Some(arrives);
        // Widened: as if it arrived as late as the link may deliver it. A
        // firmware that reads an earlier byte earlier is never behind this.
        let arrives = arrives + self.window.unwrap_or(Duration::ZERO);
        let read = self.next_read.map_or(arrives, |next| next.max(arrives));
        self.in_ring.push_back(read);
        self.next_read = Some(read + self.timing.byte_read + busy);
        let wait_over = (!busy.is_zero()).then(|| self.wait_over(now, arrives, read, busy));
        self.events.place(now, wait_over);
        read
    }

    /// By the event rules: when no byte handed out after a command read at
    /// `read` (handed out at `now`, arriving by `arrives` at the latest) can
    /// reach the robot while its EEPROM wait of `busy` lasts. When the
    /// firmware is not behind and the wait (with a bunch's reads) is over
    /// before the next event, that is once the command's own event has surely
    /// gone by: what follows rides a later one. Otherwise, once the wait is
    /// over at its latest.
    fn wait_over(&self, now: Instant, arrives: Instant, read: Instant, busy: Duration) -> Instant {
        let bunch = Events::bunch(self.robot_byte, self.timing.byte_read);
        let reads = self.timing.byte_read * u32::try_from(bunch).unwrap_or(u32::MAX);
        let behind = read > arrives + reads;
        let between_events =
            self.events.interval().is_some_and(|interval| interval > busy + reads + Duration::from_millis(1));
        match self.window {
            Some(window) if between_events && !behind => now + window,
            _ => read + self.timing.byte_read + busy,
        }
    }

    /// The firmware's next read moves to `at` (a reply just ended: it is idle).
    pub fn idle_from(&mut self, at: Instant) {
        self.next_read = Some(at);
        self.in_ring.clear();
    }

    /// A write of `bytes` was handed to the port at `now`.
    pub fn handed(&mut self, now: Instant, bytes: usize) {
        self.unconfirmed.push_back((now, bytes));
        if self.mode == PacingMode::Safe {
            self.safe_left = self.safe_left.saturating_sub(bytes);
            if self.safe_left == 0 {
                self.safe_open_at = Some(now + SAFE_PAUSE);
                self.safe_left = SAFE_BURST;
            }
        }
    }

    /// The oldest write handed out left at `at`. A write that left late moves
    /// every prediction made from its planned time by as much; returns the
    /// delay and the planned time, for the driver's own deadlines.
    pub fn written(&mut self, at: Instant) -> Option<(Instant, Duration)> {
        let (planned, _) = self.unconfirmed.pop_front()?;
        let delay = at.saturating_duration_since(planned);
        if delay.is_zero() {
            return None;
        }
        let shift = |time: &mut Instant| {
            if *time >= planned {
                *time += delay;
            }
        };
        self.in_ring.iter_mut().for_each(shift);
        self.events.shift(planned, delay);
        self.next_read.iter_mut().for_each(shift);
        self.line_free.iter_mut().for_each(shift);
        self.safe_open_at.iter_mut().for_each(shift);
        for (time, _) in &mut self.unconfirmed {
            shift(time);
        }
        if let Some(watched) = &mut self.watched {
            shift(&mut watched.expected);
        }
        Some((planned, delay))
    }

    /// A getter handed out at `sent` awaits its reply: the robot should
    /// begin printing it at `expected`.
    pub fn watch_reply(&mut self, sent: Instant, expected: Instant) {
        self.watched = Some(Watched {
            expected,
            sent,
            sample: Events::sample(self.reply_ended_at, sent),
            first: None,
            last: None,
            later_bytes: 0,
            first_bytes: 0,
            clump: (0, Duration::ZERO),
            max_gap: Duration::ZERO,
        });
    }

    /// `bytes` of the watched reply arrived at `now`.
    pub fn reply_bytes(&mut self, now: Instant, bytes: usize) {
        let Some(watched) = &mut self.watched else { return };
        match watched.last {
            // Together with the bytes before: one clump.
            Some(last) if last == now => watched.clump.0 += bytes,
            Some(last) => {
                watched.close_clump();
                watched.clump = (bytes, now.saturating_duration_since(last));
            }
            None => watched.clump = (bytes, Duration::ZERO),
        }
        if watched.first.is_some_and(|first| first != now) {
            watched.later_bytes += bytes;
        } else {
            watched.first_bytes += bytes;
        }
        watched.first.get_or_insert(now);
        watched.last = Some(now);
    }

    /// The watched reply ended whole: what its arrival says about the link.
    /// Only its variation matters: a constant delay shifts every byte alike
    /// and bunches none.
    pub fn reply_ended(&mut self) {
        let Some(mut watched) = self.watched.take() else { return };
        watched.close_clump();
        let (Some(first), Some(last)) = (watched.first, watched.last) else { return };
        self.reply_ended_at = Some(last);
        self.measured |= watched.first_bytes + watched.later_bytes >= RATE_SAMPLE_BYTES;
        self.note(&watched, first, last);
        let print = self.line_rate(&watched, first, last);
        if self.learn_events(&watched, first) {
            return;
        }
        if !watched.max_gap.is_zero() {
            self.widen(watched.max_gap, WidenReason::Bursts { gap: watched.max_gap });
            self.widen_for_lateness(&watched, first, FASTEST_REPLY_BYTE);
            return;
        }
        self.widen_for_lateness(&watched, first, print);
    }

    /// A smooth reply slower than the line the driver was given: a slower
    /// line, paced for from now on. Returns the time a byte of the reply took.
    fn line_rate(&mut self, watched: &Watched, first: Instant, last: Instant) -> Duration {
        let took = last.saturating_duration_since(first);
        if !watched.max_gap.is_zero() || watched.later_bytes < RATE_SAMPLE_BYTES || took.is_zero() {
            return FASTEST_REPLY_BYTE;
        }
        let measured = took / u32::try_from(watched.later_bytes).unwrap_or(u32::MAX);
        if self.mode == PacingMode::Adaptive && measured > self.line_byte.mul_f64(1.25) {
            self.line_byte = measured;
            // A byte takes 10 bits: bytes a second from the time per byte.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let bytes_per_s = (1.0 / measured.as_secs_f64()).round() as u32;
            let window = self.window.unwrap_or(Duration::ZERO);
            self.widened.push_back(Widened { window, reason: WidenReason::Slow { bytes_per_s } });
        }
        FASTEST_REPLY_BYTE.max(measured)
    }

    /// Adaptive only: what the reply's round trip shows of a link that
    /// delivers at connection events. Once they are learned, the window
    /// follows the last few replies (it narrows again after one held up by
    /// the host, not the link). Returns whether the event rules now pace.
    fn learn_events(&mut self, watched: &Watched, first: Instant) -> bool {
        if self.mode != PacingMode::Adaptive {
            return false;
        }
        let own = FASTEST_REPLY_BYTE * u32::try_from(watched.first_bytes).unwrap_or(u32::MAX);
        let bytes = watched.first_bytes + watched.later_bytes;
        let paced = self.events.interval().is_some();
        let learned = self.events.reply(watched.sample, (watched.sent, first), own, bytes);
        if !paced && learned.is_none() {
            return false;
        }
        self.events.gap(watched.max_gap);
        let Some(late) = self.events.robot_late() else { return false };
        // Waited out once per EEPROM write, not per byte: a wide margin costs little.
        let window = (late + late / 2 + Duration::from_millis(2)).min(MAX_WINDOW);
        let before = self.window.replace(window);
        // Said when learned, and when a reply widens it (not as it narrows again).
        let widened = before.is_none_or(|before| window > before);
        if let (Some(interval), true) = (self.events.interval(), learned.is_some() || widened) {
            self.widened.push_back(Widened { window, reason: WidenReason::Events { interval } });
        }
        true
    }

    /// What one reply showed, added to the report.
    fn note(&mut self, watched: &Watched, first: Instant, last: Instant) {
        let report = &mut self.report;
        report.replies += 1;
        let delay = first.saturating_duration_since(watched.expected);
        report.latency = Some(report.latency.map_or(delay, |latency| latency.min(delay)));
        let own = FASTEST_REPLY_BYTE * u32::try_from(watched.first_bytes).unwrap_or(u32::MAX);
        report.late = report.late.max(delay.saturating_sub(own));
        report.clump_gap = report.clump_gap.max(watched.max_gap);
        let total = watched.first_bytes + watched.later_bytes;
        report.whole |= total >= RATE_SAMPLE_BYTES && watched.first_bytes == total;
        let took = last.saturating_duration_since(first);
        if watched.later_bytes >= RATE_SAMPLE_BYTES && !took.is_zero() {
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, clippy::cast_precision_loss)]
            let rate = (watched.later_bytes as f64 / took.as_secs_f64()).round() as u32;
            report.bytes_per_s = Some(report.bytes_per_s.map_or(rate, |known| known.min(rate)));
        }
    }

    /// A slot read back different: widen (twice as wide each time).
    pub fn read_back_differed(&mut self) {
        let window = self.window.map_or(DIFFERENCE_WINDOW, |window| window * 2);
        self.widen(window, WidenReason::ReadBackDiffered);
    }

    /// A reply's first bytes came later than the robot began printing, by more
    /// than the time they need at `print` a byte: the link held them back (a
    /// bridge that hands replies over whole shows no gap inside one). That
    /// lateness counts as much as a gap.
    fn widen_for_lateness(&mut self, watched: &Watched, first: Instant, print: Duration) {
        let own = print * u32::try_from(watched.first_bytes).unwrap_or(u32::MAX);
        let late = first.saturating_duration_since(watched.expected).saturating_sub(own);
        if late > CLUMP_GAP {
            self.widen(late, WidenReason::Late { delay: late });
        }
    }

    /// Adaptive only: allow for a delivery delay of `seen`, for the rest of the session.
    fn widen(&mut self, seen: Duration, reason: WidenReason) {
        if self.mode != PacingMode::Adaptive {
            return;
        }
        let wanted = margin(seen);
        if self.window.is_some_and(|window| window >= wanted) {
            return;
        }
        self.window = Some(wanted);
        self.widened.push_back(Widened { window: wanted, reason });
    }

    /// What the pacer has to say since last asked.
    pub fn poll_widened(&mut self) -> Option<Widened> {
        self.widened.pop_front()
    }

    /// The link ended: nothing is in flight.
    pub fn reset(&mut self) {
        self.in_ring.clear();
        self.unconfirmed.clear();
        self.watched = None;
        self.events.reset();
    }
}

/// The window for a delivery delay of `seen`: beyond the longest seen — a
/// later one may be longer still, and the host's own scheduling adds to it —
/// a quarter more (at least 2 ms), and 1 ms.
fn margin(seen: Duration) -> Duration {
    (seen + (seen / 4).max(Duration::from_millis(2)) + Duration::from_millis(1)).min(MAX_WINDOW)
}

#[cfg(test)]
mod tests;
