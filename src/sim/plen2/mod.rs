//! The emulated PLEN2, faithful to `plen2.md`: no acknowledgements; malformed
//! commands silently dropped; the firmware reads one byte per main-loop pass
//! (20 µs) and blocks while it writes EEPROM (5.5 ms per `>MH`, 11 ms per
//! `>MF`, 5 ms per `>HO`/`>MA`/`>MI`, 500 ms for `>JS`), in front of a 64-byte
//! receive ring that loses what a client sends faster than that; joint
//! settings with clamping and the factory table; 90 slots of up to 20 frames,
//! never-written slots answering EEPROM garbage; `<JS` / `<MO` / `<VI` in the
//! firmware's layout (tab indentation, CRLF); playback on the 32.768 ms tick
//! and the interpreter queue. Time is emulated from the `now` it is given.

mod bridge;
mod eeprom;
mod link;
mod motion_reply;

use eeprom::{Eeprom, Slot};
use link::Link;
pub use link::{Bridge, LinkKind};

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crossbeam_channel::Sender;

use crate::link::Driver;
use motion_reply::{VERSION_REPLY, garbage_header, joint_settings_json, motion_json};

use crate::protocol::plen2::playback::{Player, Start, joint_output};
use crate::protocol::plen2::{
    ANGLE_LIMIT_TENTHS_DEG, Command, CommandParser, DEVICE_IDS, FACTORY_LIMIT_TENTHS_DEG, Joint, MAX_FRAMES,
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
    /// A playback cycle set every joint (device ids 0..=23), tenths of a degree.
    Cycle([i16; DEVICE_IDS]),
    /// A motion began: its first cycle runs at `first_cycle` on the robot's
    /// clock, each next one 32.768 ms later (a show's sound is measured against these).
    MotionStarted {
        /// The motion.
        slot: u8,
        /// When its first cycle runs.
        first_cycle: Instant,
    },
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
    player: Player,
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
            player: Player::new(),
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
            playing: self.player.playing(),
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
        match command {
            Command::SetHome { .. }
            | Command::SetMax { .. }
            | Command::SetMin { .. }
            | Command::ResetJoints
            | Command::Header(_)
            | Command::Frame(_) => self.store(command),
            Command::GetVersion | Command::GetJointSettings | Command::GetMotion { .. } => self.answer(at, command),
            _ => {
                self.drive(at, command);
                None
            }
        }
    }

    /// Live angles, home, playing and the queue: no EEPROM time.
    fn drive(&mut self, at: Instant, command: &Command) {
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
            Command::PlayMotion { slot } if self.player.playing().is_none() => self.start(at, *slot, Start::Play),
            Command::StopMotion => self.player.stop_after_last(),
            Command::Push { slot, plays } if self.queue.len() < QUEUE_LEN => self.queue.push_back((*slot, *plays)),
            Command::Pop => {
                if self.player.playing().is_none()
                    && let Some((slot, plays)) = self.queue.pop_front()
                {
                    self.start(at, slot, Start::Queued { plays });
                }
            }
            Command::ResetInterpreter => {
                self.queue.clear();
                self.player.halt();
                self.next_tick = None;
            }
            _ => {}
        }
    }

    /// Joint settings and motions written to EEPROM: how long the write keeps the firmware busy.
    fn store(&mut self, command: &Command) -> Option<Duration> {
        let device_ok = |device: u8| usize::from(device) < DEVICE_IDS;
        match command {
            // plen2.md §3: what the firmware refuses is not stored (and takes no EEPROM time).
            Command::SetHome { device, angle } if device_ok(*device) => {
                let joint = &mut self.joints[usize::from(*device)];
                if (joint.min..=joint.max).contains(angle) {
                    joint.home = *angle;
                    return Some(self.timing.joint_write);
                }
            }
            Command::SetMax { device, angle } if device_ok(*device) => {
                let joint = &mut self.joints[usize::from(*device)];
                if *angle > joint.min && *angle <= ANGLE_LIMIT_TENTHS_DEG {
                    joint.max = *angle;
                    return Some(self.timing.joint_write);
                }
            }
            Command::SetMin { device, angle } if device_ok(*device) => {
                let joint = &mut self.joints[usize::from(*device)];
                if *angle < joint.max && *angle >= -ANGLE_LIMIT_TENTHS_DEG {
                    joint.min = *angle;
                    return Some(self.timing.joint_write);
                }
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
                        header: garbage_header(),
                        frames: std::array::from_fn(|_| None),
                    });
                    slot.frames[usize::from(frame.index)] = Some((**frame).clone());
                }
                return Some(self.timing.frame_write);
            }
            _ => {}
        }
        None
    }

    /// The getters' replies, printed as the line takes them.
    fn answer(&mut self, at: Instant, command: &Command) -> Option<Duration> {
        match command {
            Command::GetVersion => return self.reply(at, VERSION_REPLY),
            Command::GetJointSettings => return self.reply(at, joint_settings_json(&self.joints).as_bytes()),
            Command::GetMotion { slot } if *slot < SLOTS => {
                let bytes = motion_json(self.slots[usize::from(*slot)].as_ref());
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

    /// Starts a motion: its cycles run from the next tick (plen2.md §6).
    fn start(&mut self, at: Instant, slot: u8, start: Start) {
        if self.player.start(&Eeprom(&self.slots), slot, start) {
            let first_cycle = *self.next_tick.get_or_insert(at + TICK);
            self.events.push_back(Plen2SimEvent::MotionStarted { slot, first_cycle });
        }
    }

    /// Runs the playback cycles due by `now`: each sets every joint to home +
    /// the cycle's value, clamped; a motion that ends gives way to the next queued one.
    fn play(&mut self, now: Instant) {
        while let Some(tick_at) = self.next_tick.filter(|t| *t <= now) {
            self.next_tick = Some(tick_at + TICK);
            let Some(values) = self.player.cycle(&Eeprom(&self.slots)) else {
                self.next_tick = None;
                return;
            };
            for (device, value) in values.iter().enumerate() {
                let JointLimits { min, max, home } = self.joints[device];
                self.angles[device] = joint_output(home, min, max, *value);
            }
            self.events.push_back(Plen2SimEvent::Cycle(self.angles));
            if self.player.playing().is_none() {
                match self.queue.pop_front() {
                    Some((slot, plays)) => {
                        self.player.start(&Eeprom(&self.slots), slot, Start::Queued { plays });
                    }
                    None => self.next_tick = None,
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
    use crate::protocol::plen2::MotionFrame;

    fn feed(sim: &mut Plen2Sim, at: Instant, bytes: &[u8]) {
        sim.handle_input(at, bytes);
        while let Some(deadline) = sim.poll_timeout().filter(|_| !sim.line.is_empty() || !sim.ring.is_empty()) {
            sim.handle_timeout(deadline);
        }
    }

    /// Everything the robot has sent, as bytes.
    fn sent(sim: &mut Plen2Sim, at: Instant) -> Vec<u8> {
        let later = at + Duration::from_secs(3600);
        std::iter::from_fn(|| sim.poll_transmit(later)).flatten().collect()
    }

    /// plen2.md §3's bytes, literally: a motion with no code prints `"codes": [`,
    /// CRLF, a tab, `],`; an erased slot says it is slot 255.
    #[test]
    fn motion_replies_are_the_firmwares_bytes() {
        let t0 = Instant::now();
        let mut sim = Plen2Sim::new(Plen2Timing::default());
        let frame = format!(">MF09000064{}", "0000".repeat(24));
        // One command at a time, as a paced client sends them (the ring holds 64 bytes).
        let step = Duration::from_millis(100);
        feed(&mut sim, t0, b">MH09Empty               0000000000001");
        // The frame as the official tool paces it: 32 bytes, then 50 ms.
        for (index, chunk) in frame.as_bytes().chunks(32).enumerate() {
            feed(&mut sim, t0 + step + u32::try_from(index).unwrap() * step / 2, chunk);
        }
        feed(&mut sim, t0 + 4 * step, b"<MO09");
        let reply = sent(&mut sim, t0);
        assert_eq!((sim.state().dropped, sim.state().executed), (0, 3), "{:?}", sim.state());
        let expected = b"{\r\n\t\"slot\": 9,\r\n\t\"name\": \"Empty               \",\r\n\t\"@frame_length\": 1,\r\n\t\"codes\": [\r\n\t],\r\n\t\"frames\": [\r\n\t\t{\r\n\t\t\t\"@index\": 0,\r\n\t\t\t\"transition_time_ms\": 100,";
        assert_eq!(String::from_utf8_lossy(&reply[..expected.len()]), String::from_utf8_lossy(expected));
        feed(&mut sim, t0 + 5 * step, b"<MO0a");
        let erased = sent(&mut sim, t0);
        assert!(erased.starts_with(b"{\r\n\t\"slot\": 255,\r\n\t\"name\": \"\xff"), "{:?}", &erased[..40]);
    }

    /// plen2.md §3: joint settings the firmware refuses are not stored.
    #[test]
    fn joint_settings_beyond_the_firmwares_rules_are_refused() {
        let t0 = Instant::now();
        let mut sim = Plen2Sim::new(Plen2Timing::default());
        let before = sim.state().joints[0];
        // >MA 901, >MI −901 (12-bit 0xc7b): outside ±900.
        feed(&mut sim, t0, b">MA00385>MI00c7b");
        assert_eq!(sim.state().joints[0], before);
        // Max 0 (taken); min 100 (≥ max: refused); max −100 (taken); min 0 (refused);
        // home 400 (outside [−900, −100]: refused); home −200 (taken).
        feed(&mut sim, t0, b">MA00000>MI00064>MA00f9c>MI00000>HO00190");
        let joint = sim.state().joints[0];
        assert_eq!((joint.min, joint.max, joint.home), (-900, -100, before.home));
        feed(&mut sim, t0, b">HO00f38>MA00384");
        let joint = sim.state().joints[0];
        assert_eq!((joint.min, joint.max, joint.home), (-900, 900, -200), "900 and a home inside are taken");
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
        let garbage = motion_json(None);
        assert!(garbage.len() > 100_000, "{}", garbage.len());
        assert!(std::str::from_utf8(&garbage).is_err());
    }
}
