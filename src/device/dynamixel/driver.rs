//! The DYNAMIXEL driver the I/O thread runs, sans IO: one packet on the bus
//! at a time (the bus is half duplex: a packet that waits for a status waits
//! for it, or for its deadline, before the next leaves). What it sends, in
//! order of need: the owner's commands (torque, LED, profile, hold), then the
//! newest goal of each servo (coalesced, one sync write for each protocol),
//! then the readings it keeps (each found servo's present position, load,
//! voltage, temperature and errors, a round every [`READ_EVERY`]).
//!
//! A scan pings Protocol 2.0 by broadcast (each servo answers in turn), then
//! Protocol 1.0 ID by ID; a servo found is read for its model, firmware and
//! limits. A status that comes after its deadline still counts for the servo
//! it names. A servo that misses [`SILENT_AFTER_MISSES`] reads in a row, with
//! nothing heard from it for [`SILENT_AFTER`], is said silent (and said
//! again when it answers).

use std::collections::{BTreeMap, VecDeque};
use std::time::{Duration, Instant};

use crate::link::Driver;
use crate::protocol::dynamixel::table::{Known, known};
use crate::protocol::dynamixel::{BROADCAST, Kind, Packet, Packets, Protocol, Read, instruction};

use super::fields::{
    LED, PROFILE_ACCELERATION, PROFILE_VELOCITY, TORQUE, Writable, le, limits_of, limits_span, read, reading_of,
    reading_span, sync_write, write,
};
use super::stream::Stream;
use super::{DynamixelCommand, DynamixelEvent, Found, Logged};
use crate::device::Direction;

/// How long a packet waits for its status (a U2D2's latency timer and the
/// servo's return delay with room to spare, as the SDK's packet timeout).
pub const ANSWER_WAIT: Duration = Duration::from_millis(30);
/// The longest a scan's 1.0 ping waits for its answer before the next ID is
/// pinged (an answer that comes later still counts: it names its servo), so
/// that the 253 IDs take under 3 s; on a link whose 2.0 servos answered the
/// broadcast, four of its round trips, at least [`PING_WAIT_LEAST`].
pub const PING_WAIT: Duration = Duration::from_millis(10);
/// The least a scan's 1.0 ping waits.
pub const PING_WAIT_LEAST: Duration = Duration::from_millis(2);
/// How long a broadcast ping waits after its last answer for another.
pub const BROADCAST_WAIT: Duration = Duration::from_millis(60);
/// A round of readings of every found servo starts this often (50 Hz).
pub const READ_EVERY: Duration = Duration::from_millis(20);
/// Reads a servo must miss in a row before it is said silent…
pub const SILENT_AFTER_MISSES: u32 = 3;
/// …with nothing heard from it for this long.
pub const SILENT_AFTER: Duration = Duration::from_millis(300);

/// What a packet on the bus waits for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Wait {
    /// No status (a sync write, a broadcast).
    Nothing,
    /// Statuses to a 2.0 broadcast ping, as many as come.
    Pings,
    /// The status of servo `id`, for `purpose`.
    Status { id: u8, purpose: Purpose },
}

/// What a read or a write is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Purpose {
    /// A 1.0 ping of a scan.
    Ping,
    /// A ping the owner asked for.
    Pong,
    /// The model number and firmware (1.0: the table's first 3 bytes).
    Identity,
    /// The limits.
    Limits,
    /// A round's reading.
    Reading,
    /// The hardware error status (2.0, read when a status raised its alert).
    HardwareError,
    /// A write, named for its refusal.
    Write(&'static str),
}

/// A packet waiting to go.
#[derive(Clone, Debug)]
struct Outgoing {
    packet: Packet,
    wait: Wait,
}

/// A servo the scan found.
#[derive(Clone, Debug)]
struct Servo {
    found: Found,
    known: Option<&'static Known>,
    misses: u32,
    heard: Instant,
    silent: bool,
    /// Its last reading's position (what a hold holds it at).
    present: Option<u32>,
    /// Its hardware error status, as last read (2.0) or said (1.0).
    hardware_error: u8,
}

/// A scan under way.
#[derive(Clone, Debug)]
struct Scan {
    /// 1.0 IDs still to ping.
    one: VecDeque<u8>,
    /// How many IDs were to ping in all (for progress).
    of: usize,
    /// When the 2.0 broadcast ping went out.
    broadcast: Option<Instant>,
    /// How long a 1.0 ping waits: [`PING_WAIT`], or four round trips of the broadcast's first answer.
    ping_wait: Duration,
}

/// The client side of a DYNAMIXEL bus.
#[derive(Debug)]
pub struct DynamixelDriver {
    packets: Packets,
    urgent: VecDeque<Outgoing>,
    goals: BTreeMap<u8, u32>,
    servos: BTreeMap<u8, Servo>,
    scan: Option<Scan>,
    /// What is on the bus, waiting, and until when.
    on_bus: Option<(Wait, Instant)>,
    out: VecDeque<Vec<u8>>,
    events: VecDeque<DynamixelEvent>,
    /// Whether readings are kept up, and the next round's start and servos.
    reading: bool,
    next_round: Option<Instant>,
    round: VecDeque<u8>,
    stream: Option<Stream>,
    /// Each servo's live profile (velocity, acceleration), put back after a stream.
    live: BTreeMap<u8, (u32, u32)>,
    /// When the link was first heard of (the packet log's seconds count from it).
    opened: Option<Instant>,
}

impl Default for DynamixelDriver {
    fn default() -> Self {
        Self {
            packets: Packets::statuses(),
            urgent: VecDeque::new(),
            goals: BTreeMap::new(),
            servos: BTreeMap::new(),
            scan: None,
            on_bus: None,
            out: VecDeque::new(),
            events: VecDeque::new(),
            reading: true,
            next_round: None,
            round: VecDeque::new(),
            stream: None,
            live: BTreeMap::new(),
            opened: None,
        }
    }
}

impl DynamixelDriver {
    fn say(&mut self, event: DynamixelEvent) {
        self.events.push_back(event);
    }

    /// Queues a write to servo `id` (or every found servo), where its model has the field.
    fn write_each(&mut self, id: Option<u8>, (name, field): Writable, value: u32) {
        let targets: Vec<(u8, Protocol, &'static Known)> = self
            .servos
            .values()
            .filter(|servo| id.is_none_or(|id| servo.found.id == id))
            .filter_map(|servo| servo.known.map(|known| (servo.found.id, servo.found.protocol, known)))
            .collect();
        for (id, protocol, known) in targets {
            if let Some((addr, size)) = field(known) {
                let packet = write(protocol, id, addr, value, size);
                self.urgent.push_back(Outgoing { packet, wait: Wait::Status { id, purpose: Purpose::Write(name) } });
            }
        }
    }

    /// The next packet to put on the bus, if any is due.
    fn next_outgoing(&mut self, now: Instant) -> Option<Outgoing> {
        if let Some(outgoing) = self.urgent.pop_front() {
            return Some(outgoing);
        }
        self.stream_due(now);
        if !self.goals.is_empty() {
            return self.goals_packet();
        }
        if let Some(scan) = &mut self.scan {
            let id = scan.one.pop_front();
            let (left, of) = (scan.one.len(), scan.of);
            return match id {
                Some(id) => {
                    self.say(DynamixelEvent::Scanning { done: of - left, of });
                    let packet = Packet::instruction(Protocol::One, id, instruction::PING, Vec::new());
                    Some(Outgoing { packet, wait: Wait::Status { id, purpose: Purpose::Ping } })
                }
                None => {
                    self.scan = None;
                    let found = self.servos.len();
                    self.say(DynamixelEvent::Scanned { found });
                    self.next_outgoing(now)
                }
            };
        }
        self.reading_packet(now)
    }

    /// The newest frame of the stream that is due becomes the goals.
    fn stream_due(&mut self, now: Instant) {
        let Some((frame, ended)) = self.stream.as_mut().and_then(|stream| stream.take_due(now)) else { return };
        for (id, position) in frame {
            self.goal(id, position);
        }
        if ended {
            self.stream = None;
            self.say(DynamixelEvent::Streamed);
            self.profiles_back();
        }
    }

    /// Servo `id` (or every servo) moves at `velocity` and `acceleration` (where its model has them).
    fn profile(&mut self, id: Option<u8>, velocity: u32, acceleration: u32) {
        self.write_each(id, PROFILE_VELOCITY, velocity);
        self.write_each(id, PROFILE_ACCELERATION, acceleration);
    }

    /// Each servo's live profile, as it was before a stream took it off.
    fn profiles_back(&mut self) {
        let live: Vec<(u8, (u32, u32))> = self.live.iter().map(|(id, profile)| (*id, *profile)).collect();
        for (id, (velocity, acceleration)) in live {
            self.profile(Some(id), velocity, acceleration);
        }
    }

    /// Servo `id`'s newest goal, within its table.
    fn goal(&mut self, id: u8, position: u32) {
        if let Some(known) = self.servos.get(&id).and_then(|servo| servo.known) {
            self.goals.insert(id, position.min(known.layout.top_position));
        }
    }

    /// One sync write for each protocol of the goals waiting (a servo's newest only).
    fn goals_packet(&mut self) -> Option<Outgoing> {
        let protocol = self.goals.keys().find_map(|id| self.servos.get(id)).map(|servo| servo.found.protocol);
        let Some(protocol) = protocol else {
            // Goals for servos never found go nowhere.
            self.goals.clear();
            return None;
        };
        let mut values = Vec::new();
        let mut at = None;
        self.goals.retain(|id, position| {
            let Some(servo) = self.servos.get(id) else { return false };
            let Some(known) = servo.known else { return false };
            if servo.found.protocol != protocol {
                return true;
            }
            at = Some((known.layout.at.goal, known.layout.at.position_size));
            values.push((*id, *position));
            false
        });
        let (addr, size) = at?;
        Some(Outgoing { packet: sync_write(protocol, addr, size, &values), wait: Wait::Nothing })
    }

    /// The next read of the round, when readings are kept and one is due.
    fn reading_packet(&mut self, now: Instant) -> Option<Outgoing> {
        if !self.reading || self.servos.is_empty() {
            return None;
        }
        if self.round.is_empty() {
            if self.next_round.is_some_and(|next| now < next) {
                return None;
            }
            self.next_round = Some(
                self.next_round.map_or(now, |next| next + READ_EVERY).max(now.checked_sub(READ_EVERY).unwrap_or(now)),
            );
            self.round = self.servos.keys().copied().collect();
        }
        while let Some(id) = self.round.pop_front() {
            let servo = &self.servos[&id];
            let Some(known) = servo.known else { continue };
            let (addr, len) = reading_span(known);
            let packet = read(servo.found.protocol, id, addr, len);
            return Some(Outgoing { packet, wait: Wait::Status { id, purpose: Purpose::Reading } });
        }
        None
    }

    /// A packet (or bytes that were none) for the packet log.
    fn log(
        &mut self,
        now: Instant,
        direction: Direction,
        packet: Option<&Packet>,
        bytes: (&[u8], usize),
        why: &'static str,
    ) {
        let opened = *self.opened.get_or_insert(now);
        self.say(DynamixelEvent::Logged(Logged::of((opened, now), direction, packet, bytes, why)));
    }

    /// Puts what is next on the bus, if the bus is free.
    fn send_next(&mut self, now: Instant) {
        while self.on_bus.is_none() {
            let Some(outgoing) = self.next_outgoing(now) else { return };
            let bytes = outgoing.packet.to_bytes();
            self.log(now, Direction::Sent, Some(&outgoing.packet), (&bytes, bytes.len()), "");
            self.out.push_back(bytes);
            match outgoing.wait {
                Wait::Nothing => {}
                Wait::Pings => {
                    if let Some(scan) = &mut self.scan {
                        scan.broadcast = Some(now);
                    }
                    self.on_bus = Some((Wait::Pings, now + BROADCAST_WAIT));
                }
                wait @ Wait::Status { purpose: Purpose::Ping, .. } => {
                    let waits = self.scan.as_ref().map_or(PING_WAIT, |scan| scan.ping_wait);
                    self.on_bus = Some((wait, now + waits));
                }
                wait => self.on_bus = Some((wait, now + ANSWER_WAIT)),
            }
        }
    }

    /// A status came.
    fn status(&mut self, now: Instant, packet: &Packet) {
        let Kind::Status(error) = packet.kind else { return };
        let id = packet.id;
        match self.on_bus {
            Some((Wait::Pings, _)) if packet.protocol == Protocol::Two => {
                if let Some(scan) = &mut self.scan
                    && let Some(sent) = scan.broadcast.take()
                {
                    scan.ping_wait = (now.saturating_duration_since(sent) * 4).clamp(PING_WAIT_LEAST, PING_WAIT);
                }
                self.found_two(now, id, &packet.params);
                // Wait on for the next servo's answer.
                self.on_bus = Some((Wait::Pings, now + BROADCAST_WAIT));
                return;
            }
            Some((Wait::Status { id: waited, purpose }, _)) if waited == id => {
                self.on_bus = None;
                self.answered(now, id, purpose, error, packet);
                return;
            }
            _ => {}
        }
        // A late status still says its servo is there.
        if let Some(servo) = self.servos.get_mut(&id) {
            servo.heard = now;
        } else if self.scan.is_some() && packet.protocol == Protocol::One && packet.params.is_empty() {
            self.found_one(id);
        }
    }

    /// A 2.0 ping's answer: its model number and firmware.
    fn found_two(&mut self, now: Instant, id: u8, params: &[u8]) {
        if self.servos.contains_key(&id) {
            return;
        }
        let (Some(number), Some(firmware)) = (le(params, 0, 2), params.get(2)) else { return };
        // Two bytes.
        #[allow(clippy::cast_possible_truncation)]
        let number = number as u16;
        self.add(now, Found { id, protocol: Protocol::Two, model_number: number, firmware: *firmware });
    }

    /// A 1.0 servo answered its ping: its model and firmware are read next.
    fn found_one(&mut self, id: u8) {
        if self.servos.contains_key(&id) {
            return;
        }
        let packet = read(Protocol::One, id, 0, 3);
        self.urgent.push_back(Outgoing { packet, wait: Wait::Status { id, purpose: Purpose::Identity } });
    }

    fn add(&mut self, now: Instant, found: Found) {
        let known = known(found.model_number);
        let id = found.id;
        self.servos
            .insert(id, Servo { found, known, misses: 0, heard: now, silent: false, present: None, hardware_error: 0 });
        self.say(DynamixelEvent::Found(found));
        if let Some(known) = known {
            let (first, len) = limits_span(known);
            let packet = read(found.protocol, id, first, len);
            self.urgent.push_back(Outgoing { packet, wait: Wait::Status { id, purpose: Purpose::Limits } });
        }
    }

    /// Servo `id` answered what it was asked for.
    fn answered(&mut self, now: Instant, id: u8, purpose: Purpose, error: u8, packet: &Packet) {
        let params = &packet.params;
        if purpose == Purpose::Ping {
            self.found_one(id);
            return;
        }
        if purpose == Purpose::Identity {
            if let (Some(number), Some(firmware)) = (le(params, 0, 2), params.get(2)) {
                #[allow(clippy::cast_possible_truncation)]
                let model_number = number as u16;
                self.add(now, Found { id, protocol: Protocol::One, model_number, firmware: *firmware });
            }
            return;
        }
        let Some(servo) = self.servos.get_mut(&id) else { return };
        servo.heard = now;
        servo.misses = 0;
        if servo.silent {
            servo.silent = false;
            self.events.push_back(DynamixelEvent::Answering { id });
        }
        let Some(known) = servo.known else { return };
        let at = known.layout.at;
        let two = packet.protocol == Protocol::Two;
        // 2.0's alert bit: the cause is in Hardware Error Status. 1.0: the bits themselves.
        if two && error & 0x80 != 0 && purpose != Purpose::HardwareError {
            if let Some(addr) = at.hardware_error {
                let packet = read(Protocol::Two, id, addr, 1);
                self.urgent.push_back(Outgoing { packet, wait: Wait::Status { id, purpose: Purpose::HardwareError } });
            }
        } else if !two {
            servo.hardware_error = error;
        } else if error & 0x80 == 0 {
            servo.hardware_error = 0;
        }
        let result = if two { error & 0x7F } else { error & !0x25 };
        match purpose {
            Purpose::Write(what) if result != 0 => {
                self.events.push_back(DynamixelEvent::Refused { id, what, error });
            }
            Purpose::Limits => {
                if let Some(limits) = limits_of(known, params) {
                    self.events.push_back(DynamixelEvent::Limits { id, limits });
                }
            }
            Purpose::Pong => self.events.push_back(DynamixelEvent::Pong { id }),
            Purpose::HardwareError => {
                if let Some(bits) = params.first() {
                    servo.hardware_error = *bits;
                }
            }
            Purpose::Reading => {
                if let Some(reading) = reading_of(known, two, params, servo.hardware_error, now) {
                    servo.present = Some(reading.position);
                    self.events.push_back(DynamixelEvent::Reading { id, reading });
                }
            }
            _ => {}
        }
    }

    /// What was on the bus waited its time out.
    fn waited_out(&mut self, now: Instant, wait: Wait) {
        let Wait::Status { id, purpose } = wait else { return };
        if matches!(purpose, Purpose::Ping | Purpose::Identity) {
            return;
        }
        let Some(servo) = self.servos.get_mut(&id) else { return };
        servo.misses += 1;
        if !servo.silent && servo.misses >= SILENT_AFTER_MISSES && now.duration_since(servo.heard) >= SILENT_AFTER {
            servo.silent = true;
            self.events.push_back(DynamixelEvent::Silent { id });
        }
    }

    /// Every found servo held where it is (its goal set to its present position).
    fn hold(&mut self) {
        self.goals.clear();
        if self.stream.take().is_some() {
            self.profiles_back();
        }
        let held: Vec<(u8, u32)> =
            self.servos.values().filter_map(|servo| Some((servo.found.id, servo.present?))).collect();
        for protocol in [Protocol::Two, Protocol::One] {
            let values: Vec<(u8, u32)> =
                held.iter().copied().filter(|(id, _)| self.servos[id].found.protocol == protocol).collect();
            let at = values.first().and_then(|(id, _)| self.servos[id].known).map(|known| known.layout.at);
            if let Some(at) = at {
                let packet = sync_write(protocol, at.goal, at.position_size, &values);
                self.urgent.push_front(Outgoing { packet, wait: Wait::Nothing });
            }
        }
    }
}

impl Driver for DynamixelDriver {
    type Command = DynamixelCommand;
    type Event = DynamixelEvent;

    fn handle_command(&mut self, now: Instant, command: DynamixelCommand) {
        match command {
            DynamixelCommand::Scan { one } => {
                self.servos.clear();
                self.goals.clear();
                self.round.clear();
                let ids: VecDeque<u8> = one.collect();
                self.scan = Some(Scan { of: ids.len(), one: ids, broadcast: None, ping_wait: PING_WAIT });
                let packet = Packet::instruction(Protocol::Two, BROADCAST, instruction::PING, Vec::new());
                self.urgent.push_back(Outgoing { packet, wait: Wait::Pings });
            }
            DynamixelCommand::Goal { id, position } => self.goal(id, position),
            DynamixelCommand::Stream { frames, every } => {
                // The frames are the motion: no profile of the servos' own may smooth or slow them.
                if self.stream.is_none() {
                    self.profile(None, 0, 0);
                }
                self.stream = Some(Stream::new(frames, every, now));
            }
            DynamixelCommand::Torque { id, on } => {
                self.write_each(id, TORQUE, u32::from(on));
            }
            DynamixelCommand::Led { id, on } => {
                self.write_each(Some(id), LED, u32::from(on));
            }
            DynamixelCommand::Profile { id, velocity, acceleration } => {
                self.live.insert(id, (velocity, acceleration));
                if self.stream.is_none() {
                    self.profile(Some(id), velocity, acceleration);
                }
            }
            DynamixelCommand::Ping { id, protocol } => {
                let packet = Packet::instruction(protocol, id, instruction::PING, Vec::new());
                self.urgent.push_back(Outgoing { packet, wait: Wait::Status { id, purpose: Purpose::Pong } });
            }
            DynamixelCommand::Read(on) => {
                self.reading = on;
                self.round.clear();
            }
            DynamixelCommand::Hold => self.hold(),
        }
    }

    fn handle_input(&mut self, now: Instant, bytes: &[u8]) {
        for read in self.packets.push(bytes) {
            match read {
                Read::Packet(packet) => {
                    let bytes = packet.to_bytes();
                    self.log(now, Direction::Received, Some(&packet), (&bytes, bytes.len()), "");
                    self.status(now, &packet);
                }
                // The reader says how many bytes it skipped, not which.
                Read::Skipped { bytes, why } => self.log(now, Direction::Skipped, None, (&[], bytes), why),
            }
        }
    }

    fn handle_timeout(&mut self, now: Instant) {
        if let Some((wait, until)) = self.on_bus
            && now >= until
        {
            self.on_bus = None;
            self.waited_out(now, wait);
        }
    }

    fn handle_disconnect(&mut self, _reason: &str) {
        self.stream = None;
        self.urgent.clear();
        self.goals.clear();
        self.on_bus = None;
        self.scan = None;
    }

    /// What is next on the bus: taken only when the I/O thread asks, after
    /// every command waiting was handled, so goals sent together coalesce.
    fn poll_transmit(&mut self, now: Instant) -> Option<Vec<u8>> {
        if self.out.is_empty() {
            self.send_next(now);
        }
        self.out.pop_front()
    }

    fn poll_event(&mut self) -> Option<DynamixelEvent> {
        self.events.pop_front()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        if let Some((_, until)) = self.on_bus {
            return Some(until);
        }
        let round = if self.reading && !self.servos.is_empty() { self.next_round } else { None };
        let frame = self.stream.as_ref().map(Stream::next_due);
        round.into_iter().chain(frame).min()
    }

    fn is_last_word(&self, command: &DynamixelCommand) -> bool {
        // STOP and relax on the way out still reach the servos.
        matches!(command, DynamixelCommand::Hold | DynamixelCommand::Torque { .. })
    }
}
