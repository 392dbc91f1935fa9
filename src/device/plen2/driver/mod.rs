//! The PLEN2 driver the I/O thread runs. The robot acknowledges nothing and
//! loses what overflows its 64-byte receive ring, so every byte is paced
//! ([`super::pacer`]) from the firmware's own timing (`plen2.md` §5) and from
//! when writes really left. Live joint moves are coalesced; STOP goes out at
//! the next command boundary, ahead of everything queued, under every pacing.
//! Sans-IO.

use std::collections::{BTreeMap, VecDeque};
use std::time::{Duration, Instant};

use crossbeam_channel::Sender;

pub use super::messages::{
    DoneSender, ERASED_REPLY_BYTES, Plen2Command, Plen2Event, Plen2Options, REPLY_IDLE, RESYNC, ReplyError, ReplyNews,
    ReplySender,
};
pub use super::pacer::Pacing;
use super::pacer::{Pacer, PacingMode};
use crate::device::{Direction, LogEntry, hex};
use crate::link::Driver;
use crate::protocol::plen2::{Command, ReplyEvent, ReplyKind, ReplyReader};

/// An erased slot's time is reckoned once this much of it has come.
const ESTIMATE_AFTER_BYTES: usize = 64 * 1024;

/// A getter's reply being awaited.
struct Awaited {
    kind: ReplyKind,
    sender: ReplySender,
    /// The silence limit, never past `overall`.
    deadline: Instant,
    /// The longest the reply may take, plus the timeout. Until the reply is
    /// recognised as the protocol's own (its first key), the first byte
    /// fixes it from the line's nominal rate and later bytes cannot move it;
    /// once recognised, it follows the rate the reply really arrives at (a
    /// Bluetooth bridge's, a slower line's), up to [`REPLY_CEILING`].
    overall: Option<Instant>,
    /// When its first byte arrived.
    first: Option<Instant>,
    bytes: usize,
    news: Option<Sender<ReplyNews>>,
    /// Part of a probe.
    probe: bool,
    /// Whether the reply was said to be an erased slot's: 0 not, 1 said, 2 said with how long.
    erased: u8,
}

/// The longest any reply may take once it is recognised: an erased slot's
/// 400 KB at a Bluetooth LE bridge's 20 bytes per 15 ms is five minutes.
pub const REPLY_CEILING: Duration = Duration::from_secs(600);

/// The most bytes a reply of `kind` can have on the line: a never-written
/// slot's garbage (255 frames of 24 outputs) for `<MO`.
fn longest_reply(kind: ReplyKind) -> usize {
    match kind {
        ReplyKind::Version => 512,
        ReplyKind::JointSettings => 8 * 1024,
        ReplyKind::Motion => 400 * 1024,
    }
}

struct Queued {
    /// `None` for the resync bytes.
    command: Option<Command>,
    bytes: Vec<u8>,
    done: Option<DoneSender>,
    reply: Option<ReplySender>,
    news: Option<Sender<ReplyNews>>,
    /// Part of a probe: its reply goes to the probe's callers.
    probe: bool,
}

/// The driver.
pub struct Plen2Driver {
    pacing: Pacing,
    pacer: Pacer,
    reply_timeout: Duration,
    line_baud: u32,
    queue: VecDeque<Queued>,
    /// The command being sent, how many of its bytes went, and whether it is urgent (STOP).
    current: Option<(Queued, usize, bool)>,
    /// STOP's commands waiting for the command on the wire to end.
    urgent: VecDeque<Queued>,
    live: BTreeMap<u8, i16>,
    waiting: Vec<(Instant, DoneSender)>,
    reader: ReplyReader,
    reply: Option<Awaited>,
    /// Who waits for the probe under way (`<VI`, then `<JS` if that answered).
    probing: Vec<ReplySender>,
    opened_at: Option<Instant>,
    /// The latest time the driver was told (deadlines are never before it).
    now: Instant,
    output: VecDeque<Vec<u8>>,
    events: VecDeque<Plen2Event>,
}

/// The most bytes written at once.
const CHUNK: usize = 64;

/// The time EEPROM writes keep the firmware busy after a command.
fn busy_after(pacing: &Pacing, command: &Command) -> Duration {
    match command {
        Command::Header(_) => pacing.header_write,
        Command::Frame(_) => pacing.frame_write,
        Command::SetHome { .. } | Command::SetMax { .. } | Command::SetMin { .. } => pacing.joint_write,
        Command::ResetJoints => pacing.factory_reset,
        _ => Duration::ZERO,
    }
}

fn reply_kind(command: &Command) -> Option<ReplyKind> {
    match command {
        Command::GetVersion => Some(ReplyKind::Version),
        Command::GetJointSettings => Some(ReplyKind::JointSettings),
        Command::GetMotion { .. } => Some(ReplyKind::Motion),
        _ => None,
    }
}

impl Plen2Driver {
    /// A driver with these options.
    pub fn new(options: Plen2Options) -> Self {
        Self {
            pacing: options.pacing,
            pacer: Pacer::new(options.mode, options.pacing, options.line_baud),
            reply_timeout: options.reply_timeout,
            line_baud: options.line_baud.max(1),
            queue: VecDeque::new(),
            current: None,
            urgent: VecDeque::new(),
            live: BTreeMap::new(),
            waiting: Vec::new(),
            reader: ReplyReader::new(),
            reply: None,
            probing: Vec::new(),
            opened_at: None,
            now: Instant::now(),
            output: VecDeque::new(),
            events: VecDeque::new(),
        }
    }

    fn log(&mut self, now: Instant, direction: Direction, name: String, fields: String, bytes: &[u8]) {
        let seconds = now.saturating_duration_since(*self.opened_at.get_or_insert(now)).as_secs_f64();
        let hex =
            if bytes.len() > 48 { format!("{} … ({} bytes)", hex(&bytes[..48]), bytes.len()) } else { hex(bytes) };
        self.events.push_back(Plen2Event::Log(LogEntry { seconds, direction, name, fields, hex }));
    }

    fn enqueue(&mut self, command: Command, done: Option<DoneSender>, reply: Option<ReplySender>) {
        let bytes = command.to_ascii().into_bytes();
        self.queue.push_back(Queued { command: Some(command), bytes, done, reply, news: None, probe: false });
    }

    /// A probe's getter, ahead of what is queued (a probe is asked for before what it measures).
    fn enqueue_probe(&mut self, command: Command) {
        let (timed, _) = crossbeam_channel::bounded(1);
        let bytes = command.to_ascii().into_bytes();
        let queued = Queued { command: Some(command), bytes, done: None, reply: Some(timed), news: None, probe: true };
        self.queue.push_front(queued);
    }

    /// A getter's reply came, or did not: to its caller — or, for a probe's,
    /// on to the next getter (`<VI` answered: `<JS`), or to the probe's callers.
    /// A probe whose first getter gets no answer stops there: a silent line
    /// is not asked twice.
    fn resolve(&mut self, awaited: &Awaited, result: Result<Vec<u8>, ReplyError>) {
        if !awaited.probe {
            let _ = awaited.sender.send(result);
            return;
        }
        if result.is_ok() && awaited.kind == ReplyKind::Version {
            // Another `<VI` while the pacing still learns from round trips, then `<JS`.
            let next = if self.pacer.wants_round_trip() { Command::GetVersion } else { Command::GetJointSettings };
            self.enqueue_probe(next);
            return;
        }
        for caller in self.probing.drain(..) {
            let _ = caller.send(result.clone());
        }
    }

    /// When the firmware will have finished everything sent so far.
    pub fn firmware_free(&self) -> Option<Instant> {
        self.pacer.firmware_free()
    }

    /// The pacing mode.
    pub fn mode(&self) -> PacingMode {
        self.pacer.mode()
    }

    #[cfg(any(test, feature = "test-api"))]
    /// The delivery delay the adaptive pacing allows for, once it widened.
    pub fn pacing_window(&self) -> Option<Duration> {
        self.pacer.window()
    }

    /// The next command to send: STOP's first, then the queue, then live moves
    /// (only when nothing else waits: they never delay an upload).
    fn next_command(&mut self) -> Option<(Queued, bool)> {
        if let Some(urgent) = self.urgent.pop_front() {
            return Some((urgent, true));
        }
        // A getter's reply must end before anything else is sent.
        if self.reply.is_some() {
            return None;
        }
        if self.queue.is_empty() && !self.live.is_empty() {
            let moves: Vec<(u8, i16)> = std::mem::take(&mut self.live).into_iter().collect();
            for (device, angle) in moves {
                self.enqueue(Command::SetAngle { device, angle }, None, None);
            }
        }
        self.queue.pop_front().map(|queued| (queued, false))
    }

    /// Hands bytes to the port as the pacer allows.
    fn pace(&mut self, now: Instant) {
        let mut chunk = Vec::new();
        // What the pacer allows now, asked once for this batch.
        let mut allowed: Option<usize> = None;
        loop {
            if self.current.is_none() {
                // STOP waits for nothing but the command on the wire; a reply
                // still being read holds everything else back.
                match self.next_command() {
                    Some((queued, urgent)) => self.current = Some((queued, 0, urgent)),
                    None => break,
                }
            }
            let urgent = self.current.as_ref().is_some_and(|(_, _, urgent)| *urgent);
            let allowed = *allowed.get_or_insert_with(|| self.pacer.room(now, urgent));
            if chunk.len() >= CHUNK.min(allowed) {
                break;
            }
            let Some((queued, sent, _)) = &mut self.current else { break };
            chunk.push(queued.bytes[*sent]);
            *sent += 1;
            let finished = *sent == queued.bytes.len();
            // The command runs when its last byte is read; EEPROM writes then block the firmware.
            let busy = match (&queued.command, finished) {
                (Some(command), true) => busy_after(&self.pacing, command),
                _ => Duration::ZERO,
            };
            let read = self.pacer.place(now, busy);
            if !finished {
                continue;
            }
            let Some((queued, _, _)) = self.current.take() else { break };
            let fields = String::from_utf8_lossy(&queued.bytes).into_owned();
            let name = queued.command.as_ref().map_or("resync", Command::code).to_string();
            self.log(now, Direction::Sent, name, fields, &queued.bytes);
            let idle = read + self.pacing.byte_read + busy;
            if let Some(done) = queued.done {
                self.waiting.push((idle, done));
            }
            if let (Some(kind), Some(sender)) = (queued.command.as_ref().and_then(reply_kind), queued.reply) {
                self.reader.expect(kind);
                self.pacer.watch_reply(now, idle);
                let deadline = idle + self.reply_timeout;
                let (news, probe) = (queued.news, queued.probe);
                self.reply = Some(Awaited {
                    kind,
                    sender,
                    deadline,
                    overall: None,
                    first: None,
                    bytes: 0,
                    news,
                    probe,
                    erased: 0,
                });
            }
        }
        if !chunk.is_empty() {
            self.pacer.handed(now, chunk.len());
            self.output.push_back(chunk);
        }
        while let Some(widened) = self.pacer.poll_widened() {
            self.log(now, Direction::Note, "pacing".into(), widened.to_string(), &[]);
            self.events.push_back(Plen2Event::Widened(widened));
        }
    }

    /// When the pacer next allows a byte, if one waits to be sent.
    fn next_send(&self, now: Instant) -> Option<Instant> {
        let more = self.current.is_some()
            || !self.urgent.is_empty()
            || (self.reply.is_none() && !(self.queue.is_empty() && self.live.is_empty()));
        more.then(|| self.pacer.next_room(now))
    }
}

impl Driver for Plen2Driver {
    type Command = Plen2Command;
    type Event = Plen2Event;

    /// STOP (`#RI`, `$HP`) goes out even when the owner closes right after sending it.
    fn is_last_word(&self, command: &Plen2Command) -> bool {
        matches!(command, Plen2Command::Stop)
    }

    fn handle_command(&mut self, now: Instant, command: Plen2Command) {
        match command {
            Plen2Command::Send { command, done } => self.enqueue(command, done, None),
            Plen2Command::Get { command, reply, news } => {
                self.enqueue(command, None, Some(reply));
                if let Some(queued) = self.queue.back_mut() {
                    queued.news = news;
                }
            }
            Plen2Command::LiveAngles(moves) => self.live.extend(moves),
            Plen2Command::Stop => {
                self.live.clear();
                // Nothing still queued goes out after STOP: a play, a play
                // list's start or a pose queued a moment before would move the
                // robot after it (behind a slow or bursty link, long after).
                // Whoever waits for what is dropped is told it was not sent.
                for queued in self.queue.drain(..) {
                    if let Some(done) = queued.done {
                        let _ = done.send(Err(ReplyError::Stopped));
                    }
                    match (queued.reply, queued.probe) {
                        (Some(reply), false) => {
                            let _ = reply.send(Err(ReplyError::Stopped));
                        }
                        (_, true) => {
                            for reply in self.probing.drain(..) {
                                let _ = reply.send(Err(ReplyError::Stopped));
                            }
                        }
                        (None, false) => {}
                    }
                }
                // Ahead of everything queued, after the command on the wire (cutting
                // it would make its tail read as garbage arguments), under every pacing.
                self.urgent.clear();
                for command in [Command::ResetInterpreter, Command::HomePosition] {
                    let bytes = command.to_ascii().into_bytes();
                    self.urgent.push_back(Queued {
                        bytes,
                        command: Some(command),
                        done: None,
                        reply: None,
                        news: None,
                        probe: false,
                    });
                }
            }
            Plen2Command::Resync => {
                self.queue.push_back(Queued {
                    command: None,
                    bytes: RESYNC.to_vec(),
                    done: None,
                    reply: None,
                    news: None,
                    probe: false,
                });
            }
            Plen2Command::ReadBackDiffered => self.pacer.read_back_differed(),
            Plen2Command::Probe { reply } => {
                if !self.probing.is_empty() {
                    // One under way already: its answer is this one's too.
                    self.probing.push(reply);
                } else if self.pacer.wants_measurement() {
                    self.probing.push(reply);
                    self.enqueue_probe(Command::GetVersion);
                } else {
                    let _ = reply.send(Ok(Vec::new()));
                }
            }
        }
        self.now = now;
        self.pace(now);
    }

    fn handle_input(&mut self, now: Instant, bytes: &[u8]) {
        self.now = self.now.max(now);
        self.reader.push(bytes);
        let (timeout, baud) = (self.reply_timeout, self.line_baud);
        if self.reply.is_some() {
            self.pacer.reply_bytes(now, bytes.len());
        }
        let recognised = self.reader.recognised();
        let mut newly_erased = false;
        if let Some(awaited) = &mut self.reply {
            awaited.bytes += bytes.len();
            let first = *awaited.first.get_or_insert(now);
            // 10 bits a byte on the line; once the reply is the protocol's own,
            // the rate it really arrives at, if slower.
            let nominal = f64::from(baud) / 10.0;
            let elapsed = now.saturating_duration_since(first).as_secs_f64();
            let measured = if elapsed > 0.0 { awaited.bytes as f64 / elapsed } else { f64::INFINITY };
            let rate = if recognised { nominal.min(measured) } else { nominal };
            let longest = Duration::from_secs_f64(longest_reply(awaited.kind) as f64 / rate.max(1.0));
            let overall = first + longest.min(REPLY_CEILING) + timeout;
            let overall = match awaited.overall {
                Some(fixed) if !recognised => fixed,
                Some(earlier) => earlier.max(overall),
                None => overall,
            };
            awaited.overall = Some(overall);
            awaited.deadline = (now + timeout).min(overall);
            // An erased slot is said at once, and again once the rate it comes at tells how long it takes.
            let told = awaited.erased;
            if told < 2 && self.reader.erased_slot() == Some(true) {
                let estimate = awaited.bytes >= ESTIMATE_AFTER_BYTES && elapsed > 0.0;
                if told == 0 || estimate {
                    awaited.erased = if estimate { 2 } else { 1 };
                    let remaining = estimate.then(|| {
                        let left = ERASED_REPLY_BYTES.saturating_sub(awaited.bytes) as f64;
                        // At the rate it really comes (a USB CDC line can beat its nominal baud).
                        Duration::from_secs_f64(left / measured.max(1.0))
                    });
                    if let Some(news) = &awaited.news {
                        let _ = news.send(ReplyNews::Erased { remaining });
                    }
                    newly_erased = told == 0;
                }
            }
        }
        if newly_erased {
            let text = "never written: the robot prints its erased memory (about 300 KB) before it reads anything else; nothing is sent meanwhile";
            self.log(now, Direction::Note, "erased slot".into(), text.into(), &[]);
        }
        self.take_replies(now);
        self.pace(now);
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.now = self.now.max(now);
        if let Some(awaited) = self.reply.take_if(|awaited| now >= awaited.deadline) {
            // A reply that began and then stopped (or ran past the longest
            // reply's time) is the protocol's own, cut short: worth asking
            // again. Only bytes that never began one are another protocol.
            let error = if awaited.bytes == 0 || self.reader.recognised() {
                ReplyError::Timeout { timeout_ms: u64::try_from(self.reply_timeout.as_millis()).unwrap_or(u64::MAX) }
            } else {
                ReplyError::NotThisProtocol { bytes: awaited.bytes }
            };
            self.reader.abandon();
            self.resolve(&awaited, Err(error));
        }
        let (due, later): (Vec<_>, Vec<_>) =
            std::mem::take(&mut self.waiting).into_iter().partition(|(at, _)| *at <= now);
        self.waiting = later;
        for (_, done) in due {
            let _ = done.send(Ok(()));
        }
        self.pace(now);
    }

    fn handle_disconnect(&mut self, _reason: &str) {
        if let Some(awaited) = self.reply.take() {
            let _ = awaited.sender.send(Err(ReplyError::Disconnected));
        }
        for caller in self.probing.drain(..) {
            let _ = caller.send(Err(ReplyError::Disconnected));
        }
        for queued in self.queue.drain(..) {
            if let Some(reply) = queued.reply {
                let _ = reply.send(Err(ReplyError::Disconnected));
            }
        }
        self.current = None;
        self.urgent.clear();
        self.pacer.reset();
        self.waiting.clear();
    }

    fn poll_transmit(&mut self, _now: Instant) -> Option<Vec<u8>> {
        self.output.pop_front()
    }

    fn handle_written(&mut self, now: Instant, _bytes: usize) {
        self.now = self.now.max(now);
        // A write that left late moves every prediction made from it: the
        // robot reads it later, so what follows must wait as much.
        if let Some((planned, delay)) = self.pacer.written(now) {
            for (at, _) in &mut self.waiting {
                if *at >= planned {
                    *at += delay;
                }
            }
            if let Some(awaited) = &mut self.reply
                && awaited.overall.is_none()
                && awaited.deadline >= planned
            {
                awaited.deadline += delay;
            }
        }
        self.pace(now);
    }

    fn poll_event(&mut self) -> Option<Plen2Event> {
        self.events.pop_front()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        let waiting = self.waiting.iter().map(|(at, _)| *at).min();
        let reply = self.reply.as_ref().map(|awaited| awaited.deadline);
        [self.next_send(self.now), waiting, reply].into_iter().flatten().min()
    }
}

impl Plen2Driver {
    /// Every reply (or garbage, or bytes outside one) the reader has finished: logged, and the awaited request answered.
    fn take_replies(&mut self, now: Instant) {
        while let Some(event) = self.reader.poll() {
            match event {
                ReplyEvent::Complete { kind, bytes } => {
                    let text = String::from_utf8_lossy(&bytes);
                    let summary: String = text.split_whitespace().collect::<Vec<_>>().join(" ");
                    let summary: String = summary.chars().take(120).collect();
                    self.log(now, Direction::Received, format!("{kind:?} reply"), summary, &bytes);
                    // What its arrival says about the link (before a probe
                    // asks whether to time another); the firmware is idle again.
                    self.pacer.reply_ended();
                    self.pacer.idle_from(now);
                    if let Some(awaited) = self.reply.take() {
                        self.resolve(&awaited, Ok(bytes));
                    }
                }
                ReplyEvent::Oversized { kind, bytes } => {
                    self.log(
                        now,
                        Direction::Received,
                        format!("{kind:?} reply"),
                        format!("{} of garbage", crate::device::bytes(bytes)),
                        &[],
                    );
                    if let Some(awaited) = self.reply.take() {
                        self.resolve(&awaited, Err(ReplyError::Garbage { bytes }));
                    }
                    self.pacer.reply_ended();
                    self.pacer.idle_from(now);
                }
                ReplyEvent::Ignored { bytes } => {
                    self.log(now, Direction::Skipped, format!("{bytes} byte(s) outside a reply"), String::new(), &[]);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests;
