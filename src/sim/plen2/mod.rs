//! The emulated PLEN2, faithful to `plen2.md`: no acknowledgements; malformed
//! commands silently dropped; the firmware reads one byte per main-loop pass
//! (20 µs) and blocks while it writes EEPROM (5.5 ms per `>MH`, 11 ms per
//! `>MF`, 5 ms per `>HO`/`>MA`/`>MI`, 500 ms for `>JS`), in front of a 64-byte
//! receive ring that loses what a client sends faster than that; joint
//! settings with clamping and the factory table; 90 slots of up to 20 frames,
//! never-written slots answering EEPROM garbage; `<JS` / `<MO` / `<VI` in the
//! firmware's layout (tab indentation, CRLF); playback on the 32.768 ms tick
//! and the interpreter queue. Time is emulated from the `now` it is given.

mod link;
mod motion_reply;

use link::Link;
pub use link::LinkKind;

use std::collections::VecDeque;
use std::fmt::Write as _;
use std::time::{Duration, Instant};

use crossbeam_channel::Sender;

use crate::link::Driver;
use motion_reply::{garbage_header, motion_json};

use crate::protocol::plen2::{
    Command, CommandParser, DEVICE_IDS, FACTORY_LIMIT_TENTHS_DEG, Joint, MAX_FRAMES, MotionFrame, MotionHeader,
    ParseError, QUEUE_LEN, SLOTS,
};

/// How the emulated robot's firmware spends its time.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plen2Timing {
    /// One byte on the line to the robot (2,000,000 baud, 10 bits).
    pub line_byte: Duration,
    /// One byte of a reply to the host (USB full speed, about 1 MB/s).
    pub reply_byte: Duration,
    /// One main-loop pass, reading one byte.
    pub byte_read: Duration,
    /// EEPROM write of a `>MH`.
    pub header_write: Duration,
    /// EEPROM write of a `>MF`.
    pub frame_write: Duration,
    /// EEPROM write of a `>HO` / `>MA` / `>MI`.
    pub joint_write: Duration,
    /// `>JS`.
    pub factory_reset: Duration,
    /// Bytes the receive ring holds.
    pub ring_bytes: usize,
}

impl Default for Plen2Timing {
    fn default() -> Self {
        Self {
            line_byte: Duration::from_micros(5),
            reply_byte: Duration::from_micros(1),
            byte_read: Duration::from_micros(20),
            header_write: Duration::from_micros(5_500),
            frame_write: Duration::from_millis(11),
            joint_write: Duration::from_millis(5),
            factory_reset: Duration::from_millis(500),
            ring_bytes: 64,
        }
    }
}

/// The playback tick.
pub const TICK: Duration = Duration::from_micros(32_768);

/// One joint's stored settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct JointLimits {
    /// Min, tenths of a degree.
    pub min: i16,
    /// Max.
    pub max: i16,
    /// Home.
    pub home: i16,
}

fn factory() -> [JointLimits; DEVICE_IDS] {
    let mut table =
        [JointLimits { min: -FACTORY_LIMIT_TENTHS_DEG, max: FACTORY_LIMIT_TENTHS_DEG, home: 0 }; DEVICE_IDS];
    for joint in Joint::ALL {
        table[usize::from(joint.device_id())].home = joint.factory_home_tenths_deg();
    }
    table
}

#[derive(Clone, Debug, PartialEq, Eq)]
struct Slot {
    header: MotionHeader,
    frames: [Option<MotionFrame>; MAX_FRAMES],
}

#[derive(Clone, Debug)]
struct Playback {
    slot: u8,
    frame: usize,
    ticks_left: u32,
    ticks_total: u32,
    from: [i16; DEVICE_IDS],
    loops_left: Option<u32>,
    jump: bool,
    plays_left: Option<u32>,
    stop_after_pass: bool,
}

/// The robot as a test inspects it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plen2State {
    /// Every joint's angle now, tenths of a degree, by device id.
    pub angles: [i16; DEVICE_IDS],
    /// The stored joint settings.
    pub joints: [JointLimits; DEVICE_IDS],
    /// The slot playing, if any.
    pub playing: Option<u8>,
    /// Bytes lost because the receive ring was full.
    pub lost_bytes: u64,
    /// Commands executed.
    pub executed: u64,
    /// Commands dropped as malformed.
    pub dropped: u64,
    /// Slots holding a header.
    pub written_slots: Vec<u8>,
    /// Motions queued.
    pub queued: usize,
}

/// What the owner tells the emulated robot.
#[derive(Debug)]
pub enum Plen2SimCommand {
    /// Report the state now.
    Inspect(Sender<Plen2State>),
    /// A fault: skip the next `skip` bytes received, then lose the `lose`
    /// after them (as a glitching cable would), counted as lost.
    LoseBytes {
        /// Bytes let through first.
        skip: usize,
        /// Bytes then lost.
        lose: usize,
    },
}

/// What the emulated robot reports.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Plen2SimEvent {
    /// A command was executed.
    Executed(Command),
    /// A command was dropped.
    Dropped(ParseError),
    /// Bytes were lost: the ring was full.
    Lost(u64),
}

/// The emulated robot.
#[derive(Debug)]
pub struct Plen2Sim {
    timing: Plen2Timing,
    /// The line from the host: each byte with when it reaches the ring.
    line: VecDeque<(Instant, u8)>,
    link: Link,
    /// The owner's fault: (bytes to let through, bytes then to lose).
    glitch: Option<(usize, usize)>,
    ring: VecDeque<(Instant, u8)>,
    ready_at: Option<Instant>,
    parser: CommandParser,
    joints: [JointLimits; DEVICE_IDS],
    angles: [i16; DEVICE_IDS],
    slots: Vec<Option<Slot>>,
    playback: Option<Playback>,
    queue: VecDeque<(u8, u8)>,
    next_tick: Option<Instant>,
    lost: u64,
    executed: u64,
    dropped: u64,
    /// Reply chunks and when each has crossed the line.
    output: VecDeque<(Instant, Vec<u8>)>,
    events: VecDeque<Plen2SimEvent>,
}

impl Plen2Sim {
    /// A robot fresh from the factory: factory joint settings, no motion written.
    pub fn new(timing: Plen2Timing) -> Self {
        let joints = factory();
        let angles = joints.map(|joint| joint.home);
        let link = Link::new(LinkKind::Clean, timing.line_byte, timing.reply_byte);
        Self {
            timing,
            line: VecDeque::new(),
            link,
            glitch: None,
            ring: VecDeque::new(),
            ready_at: None,
            parser: CommandParser::default(),
            joints,
            angles,
            slots: vec![None; usize::from(SLOTS)],
            playback: None,
            queue: VecDeque::new(),
            next_tick: None,
            lost: 0,
            executed: 0,
            dropped: 0,
            output: VecDeque::new(),
            events: VecDeque::new(),
        }
    }

    /// The same robot behind another kind of line.
    pub fn with_link(mut self, kind: LinkKind) -> Self {
        self.link = Link::new(kind, self.timing.line_byte, self.timing.reply_byte);
        self
    }

    /// The state now.
    pub fn state(&self) -> Plen2State {
        Plen2State {
            angles: self.angles,
            joints: self.joints,
            playing: self.playback.as_ref().map(|p| p.slot),
            lost_bytes: self.lost,
            executed: self.executed,
            dropped: self.dropped,
            written_slots: (0..SLOTS).filter(|s| self.slots[usize::from(*s)].is_some()).collect(),
            queued: self.queue.len(),
        }
    }

    fn clamp(&self, device: usize, angle: i16) -> i16 {
        let limits = self.joints[device];
        angle.clamp(limits.min.min(limits.max), limits.max.max(limits.min))
    }

    /// Runs the line, the ring and the firmware up to `now`.
    fn advance(&mut self, now: Instant) {
        loop {
            let arrival = self.line.front().map(|(t, _)| *t).filter(|t| *t <= now);
            let consume =
                self.ring.front().map(|(t, _)| self.ready_at.map_or(*t, |ready| ready.max(*t))).filter(|t| *t <= now);
            match (arrival, consume) {
                (Some(a), Some(c)) if c < a => self.consume(c),
                (Some(_), _) => {
                    let Some((at, byte)) = self.line.pop_front() else { break };
                    if self.ring.len() < self.timing.ring_bytes {
                        self.ring.push_back((at, byte));
                    } else {
                        self.lost += 1;
                        self.events.push_back(Plen2SimEvent::Lost(self.lost));
                    }
                }
                (None, Some(c)) => self.consume(c),
                (None, None) => break,
            }
        }
        self.play(now);
    }

    fn consume(&mut self, at: Instant) {
        let Some((_, byte)) = self.ring.pop_front() else { return };
        self.ready_at = Some(at + self.timing.byte_read);
        match self.parser.push(byte) {
            Some(Ok(command)) => {
                self.executed += 1;
                let busy = self.execute(at, &command);
                if let Some(busy) = busy {
                    self.ready_at = Some(at + self.timing.byte_read + busy);
                }
                self.events.push_back(Plen2SimEvent::Executed(command));
            }
            Some(Err(error)) => {
                self.dropped += 1;
                self.events.push_back(Plen2SimEvent::Dropped(error));
            }
            None => {}
        }
    }

    /// Executes a command; returns how long the firmware then blocks.
    /// Stores what `commands` write (joint settings, motions) as if written
    /// long before power-on: no line, no ring, no EEPROM wait, not counted.
    pub fn preload(&mut self, commands: &[Command]) {
        let now = Instant::now();
        for command in commands {
            self.execute(now, command);
        }
        self.events.clear();
    }

    fn execute(&mut self, at: Instant, command: &Command) -> Option<Duration> {
        let device_ok = |device: u8| usize::from(device) < DEVICE_IDS;
        match command {
            Command::SetAngle { device, angle } if device_ok(*device) => {
                let d = usize::from(*device);
                self.angles[d] = self.clamp(d, *angle);
            }
            Command::SetDiff { device, diff } if device_ok(*device) => {
                let d = usize::from(*device);
                self.angles[d] = self.clamp(d, self.joints[d].home.saturating_add(*diff));
            }
            Command::HomePosition => {
                for d in 0..DEVICE_IDS {
                    self.angles[d] = self.joints[d].home;
                }
            }
            Command::PlayMotion { slot } if self.playback.is_none() => self.start(at, *slot, None),
            Command::StopMotion => {
                if let Some(playback) = &mut self.playback {
                    playback.stop_after_pass = true;
                    playback.loops_left = Some(0);
                    playback.jump = false;
                }
            }
            Command::Push { slot, plays } if self.queue.len() < QUEUE_LEN => self.queue.push_back((*slot, *plays)),
            Command::Pop => {
                if self.playback.is_none()
                    && let Some((slot, plays)) = self.queue.pop_front()
                {
                    self.start(at, slot, Some(plays));
                }
            }
            Command::ResetInterpreter => {
                self.queue.clear();
                self.playback = None;
                self.next_tick = None;
            }
            Command::SetHome { device, angle } if device_ok(*device) => {
                self.joints[usize::from(*device)].home = *angle;
                return Some(self.timing.joint_write);
            }
            Command::SetMax { device, angle } if device_ok(*device) => {
                self.joints[usize::from(*device)].max = *angle;
                return Some(self.timing.joint_write);
            }
            Command::SetMin { device, angle } if device_ok(*device) => {
                self.joints[usize::from(*device)].min = *angle;
                return Some(self.timing.joint_write);
            }
            Command::ResetJoints => {
                self.joints = factory();
                return Some(self.timing.factory_reset);
            }
            Command::Header(header) => {
                let slot = self.slots[usize::from(header.slot)]
                    .get_or_insert_with(|| Slot { header: header.clone(), frames: std::array::from_fn(|_| None) });
                slot.header = header.clone();
                return Some(self.timing.header_write);
            }
            Command::Frame(frame) => {
                if usize::from(frame.index) < MAX_FRAMES {
                    // A frame written before its header lands in an otherwise garbage slot.
                    let slot = self.slots[usize::from(frame.slot)].get_or_insert_with(|| Slot {
                        header: garbage_header(frame.slot),
                        frames: std::array::from_fn(|_| None),
                    });
                    slot.frames[usize::from(frame.index)] = Some((**frame).clone());
                }
                return Some(self.timing.frame_write);
            }
            Command::GetVersion => {
                return self.reply(at, b"{\r\n\t\"device\": \"PLEN2\",\r\n\t\"codename\": \"Cytisus\",\r\n\t\"version\": \"1.4.2\"\r\n}\r\n");
            }
            Command::GetJointSettings => {
                let mut text = String::from("[\r\n");
                for (device, joint) in self.joints.iter().enumerate() {
                    let comma = if device + 1 < DEVICE_IDS { "," } else { "" };
                    let _ = write!(
                        text,
                        "\t{{\r\n\t\t\"@device\": {device},\r\n\t\t\"max\": {},\r\n\t\t\"min\": {},\r\n\t\t\"home\": {}\r\n\t}}{comma}\r\n",
                        joint.max, joint.min, joint.home
                    );
                }
                text.push_str("]\r\n");
                return self.reply(at, text.as_bytes());
            }
            Command::GetMotion { slot } if *slot < SLOTS => {
                let bytes = motion_json(*slot, self.slots[usize::from(*slot)].as_ref());
                return self.reply(at, &bytes);
            }
            _ => {}
        }
        None
    }

    /// Queues a reply, each piece due when the link delivers it; the
    /// firmware is busy while it prints (as fast as the line takes it).
    fn reply(&mut self, at: Instant, bytes: &[u8]) -> Option<Duration> {
        let (pieces, printed) = self.link.carry_to_host(at, bytes);
        self.output.extend(pieces);
        Some(printed.saturating_duration_since(at))
    }

    fn start(&mut self, at: Instant, slot: u8, plays: Option<u8>) {
        let Some(stored) = self.slots.get(usize::from(slot)).and_then(Option::as_ref) else { return };
        let header = &stored.header;
        let loops_left = match plays {
            // Queued: plays ≥ 2 loops the motion (or its loop range); 1 disables its loop.
            Some(1) => Some(0),
            Some(0) => None,
            Some(n) => Some(u32::from(n) - 1),
            None if header.loop_on && header.loop_count == 0xff => None,
            None if header.loop_on => Some(u32::from(header.loop_count)),
            None => Some(0),
        };
        self.playback = Some(Playback {
            slot,
            frame: 0,
            ticks_left: 0,
            ticks_total: 0,
            from: self.angles,
            loops_left,
            jump: plays.is_none() && header.jump_on,
            plays_left: plays.map(u32::from),
            stop_after_pass: false,
        });
        self.begin_frame(0);
        self.next_tick = Some(at + TICK);
    }

    fn begin_frame(&mut self, index: usize) {
        let angles = self.angles;
        let Some(playback) = &mut self.playback else { return };
        let transition = self.slots[usize::from(playback.slot)]
            .as_ref()
            .and_then(|slot| slot.frames.get(index).cloned().flatten())
            .map_or(0, |frame| frame.transition_ms);
        // The firmware counts transitions in 32.768 ms ticks (8 bits).
        let ticks = u32::try_from(u64::from(transition) * 1000 / 32_768).unwrap_or(1).clamp(1, 255);
        playback.frame = index;
        playback.ticks_left = ticks;
        playback.ticks_total = ticks;
        playback.from = angles;
    }

    fn play(&mut self, now: Instant) {
        while let Some(tick_at) = self.next_tick.filter(|t| *t <= now) {
            self.next_tick = Some(tick_at + TICK);
            let Some(playback) = &mut self.playback else {
                self.next_tick = None;
                return;
            };
            let Some(slot) = self.slots[usize::from(playback.slot)].clone() else {
                self.playback = None;
                return;
            };
            let target = slot.frames[playback.frame].as_ref().map_or([0; DEVICE_IDS], |frame| frame.values);
            playback.ticks_left = playback.ticks_left.saturating_sub(1);
            let done = playback.ticks_total - playback.ticks_left;
            let from = playback.from;
            let total = playback.ticks_total.max(1);
            for device in 0..DEVICE_IDS {
                let goal = i32::from(self.joints[device].home) + i32::from(target[device]);
                let value = i32::from(from[device])
                    + (goal - i32::from(from[device])) * i32::try_from(done).unwrap_or(0)
                        / i32::try_from(total).unwrap_or(1);
                let value = i16::try_from(value).unwrap_or(0);
                self.angles[device] = self.clamp(device, value);
            }
            let Some(playback) = &mut self.playback else { return };
            if playback.ticks_left > 0 {
                continue;
            }
            let header = &slot.header;
            let frames = usize::from(header.frame_count).min(MAX_FRAMES);
            let looping = header.loop_on || playback.plays_left.is_some();
            let (begin, end) = if header.loop_on {
                (usize::from(header.loop_begin), usize::from(header.loop_end))
            } else {
                (0, frames.saturating_sub(1))
            };
            let next = playback.frame + 1;
            if looping && playback.frame == end && playback.loops_left != Some(0) {
                if let Some(left) = &mut playback.loops_left {
                    *left -= 1;
                }
                self.begin_frame(begin);
            } else if next < frames {
                self.begin_frame(next);
            } else if playback.jump && !playback.stop_after_pass {
                let jump = header.jump_slot;
                self.playback = None;
                self.start(tick_at, jump, None);
            } else {
                self.playback = None;
                if let Some((slot, plays)) = self.queue.pop_front() {
                    self.start(tick_at, slot, Some(plays));
                } else {
                    self.next_tick = None;
                }
            }
        }
    }
}

impl Driver for Plen2Sim {
    type Command = Plen2SimCommand;
    type Event = Plen2SimEvent;

    fn handle_command(&mut self, now: Instant, command: Plen2SimCommand) {
        self.advance(now);
        match command {
            Plen2SimCommand::Inspect(reply) => {
                let _ = reply.send(self.state());
            }
            Plen2SimCommand::LoseBytes { skip, lose } => self.glitch = Some((skip, lose)),
        }
    }

    fn handle_input(&mut self, now: Instant, bytes: &[u8]) {
        let mut kept = Vec::with_capacity(bytes.len());
        for &byte in bytes {
            match &mut self.glitch {
                Some((0, 0)) | None => self.glitch = None,
                Some((0, lose)) => {
                    *lose -= 1;
                    self.lost += 1;
                    self.events.push_back(Plen2SimEvent::Lost(self.lost));
                    continue;
                }
                Some((skip, _)) => *skip -= 1,
            }
            kept.push(byte);
        }
        // Each byte reaches the ring when the link delivers it.
        let arrivals = self.link.carry_to_robot(now, kept.len());
        self.line.extend(arrivals.into_iter().zip(kept));
        self.advance(now);
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.advance(now);
    }

    fn handle_disconnect(&mut self, _reason: &str) {}

    fn poll_transmit(&mut self, now: Instant) -> Option<Vec<u8>> {
        if self.output.front().is_some_and(|(due, _)| *due <= now) {
            return self.output.pop_front().map(|(_, bytes)| bytes);
        }
        None
    }

    fn poll_event(&mut self) -> Option<Plen2SimEvent> {
        self.events.pop_front()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        let arrival = self.line.front().map(|(t, _)| *t);
        let consume = self.ring.front().map(|(t, _)| self.ready_at.map_or(*t, |ready| ready.max(*t)));
        let reply = self.output.front().map(|(due, _)| *due);
        [arrival, consume, self.next_tick, reply].into_iter().flatten().min()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn feed(sim: &mut Plen2Sim, at: Instant, bytes: &[u8]) {
        sim.handle_input(at, bytes);
        while let Some(deadline) = sim.poll_timeout().filter(|_| !sim.line.is_empty() || !sim.ring.is_empty()) {
            sim.handle_timeout(deadline);
        }
    }

    #[test]
    fn a_burst_overflows_the_ring_and_a_paced_stream_does_not() {
        let t0 = Instant::now();
        let frame = Command::Frame(Box::new(MotionFrame { slot: 0, index: 0, transition_ms: 100, values: [0; 24] }));
        let bytes = frame.to_ascii().repeat(3);
        let mut careless = Plen2Sim::new(Plen2Timing::default());
        feed(&mut careless, t0, bytes.as_bytes());
        assert!(careless.state().lost_bytes > 0, "three frames at once overflow the ring");

        let mut paced = Plen2Sim::new(Plen2Timing::default());
        let mut at = t0;
        for chunk in bytes.as_bytes().chunks(40) {
            feed(&mut paced, at, chunk);
            // 40 bytes read at 20 µs, plus an EEPROM write when a frame ended.
            at += Duration::from_millis(14);
        }
        let state = paced.state();
        assert_eq!(state.lost_bytes, 0);
        assert_eq!(state.executed, 3);
    }

    #[test]
    fn angles_are_clamped_to_the_joint_limits_and_never_written_slots_answer_garbage() {
        let t0 = Instant::now();
        let mut sim = Plen2Sim::new(Plen2Timing::default());
        feed(&mut sim, t0, b"$AN00fff$AN0c384");
        assert_eq!(sim.state().angles[0], -1, "−1 is inside the limits");
        assert_eq!(sim.state().angles[12], 900, "900 is the factory max");
        let garbage = motion_json(5, None);
        assert!(garbage.len() > 100_000, "{}", garbage.len());
        assert!(std::str::from_utf8(&garbage).is_err());
    }
}
