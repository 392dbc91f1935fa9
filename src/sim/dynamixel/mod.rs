//! An emulated DYNAMIXEL bus: several servos of different models and
//! protocols on one line, as on a U2D2 — each with its control table
//! (`table.rs`), answering pings, reads, writes, sync reads and sync writes
//! in its own protocol and ignoring the other's packets; each waiting its
//! return delay before it answers and answering only as its status return
//! level says; refusing a write outside its writable fields (and, on an
//! X-series, to its EEPROM area while its torque is on); each with its torque
//! on moving toward its goal at its profile velocity (AX: moving speed).

use std::collections::VecDeque;
use std::time::{Duration, Instant};

pub use crate::protocol::dynamixel::table::{AX_12A, MODELS, Model, XL430_W250, XM430_W350};

use crate::link::Driver;
use crate::protocol::dynamixel::{BROADCAST, Kind, Packet, Packets, Protocol, Read, instruction};

/// How often the servos' positions move on, while one moves.
const MOTION_STEP: Duration = Duration::from_millis(5);

/// Protocol 2.0's result numbers (the status's error byte, bits 0–6).
mod result {
    /// The instruction is not one the servo knows.
    pub const INSTRUCTION: u8 = 0x02;
    /// The data is too long or too short for the instruction.
    pub const DATA_LENGTH: u8 = 0x05;
    /// A write where no writable field is, or to the EEPROM with the torque on.
    pub const ACCESS: u8 = 0x07;
    /// Bit 7: the servo has a hardware error (read Hardware Error Status).
    pub const ALERT: u8 = 0x80;
}

/// Protocol 1.0's error bits (the status's error byte).
mod error_one {
    /// An instruction not defined, or a write to a field that is read-only.
    pub const INSTRUCTION: u8 = 0x40;
    /// A value out of range (1.0 says so for a write it cannot take).
    pub const RANGE: u8 = 0x08;
}

/// One emulated servo.
#[derive(Debug)]
pub struct Servo {
    model: &'static Model,
    table: Vec<u8>,
    /// 1.0: the error bits its statuses carry (2.0 keeps them in its table).
    errors: u8,
    /// Where it is, in position units (fractional while it moves).
    at: f64,
}

impl Servo {
    /// A servo of `model` with ID `id`, as the factory leaves it otherwise.
    pub fn new(model: &'static Model, id: u8) -> Self {
        let mut servo = Self { model, table: model.factory(), errors: 0, at: 0.0 };
        servo.table[usize::from(model.at.id)] = id;
        servo.at = f64::from(servo.read(model.at.present, 2));
        servo
    }

    fn id(&self) -> u8 {
        self.table[usize::from(self.model.at.id)]
    }

    /// `len` (1, 2 or 4) bytes at `addr`, little-endian.
    fn read(&self, addr: u16, len: usize) -> u32 {
        let at = usize::from(addr);
        let mut bytes = [0; 4];
        bytes[..len].copy_from_slice(&self.table[at..at + len]);
        u32::from_le_bytes(bytes)
    }

    fn write(&mut self, addr: u16, value: u32, len: usize) {
        let at = usize::from(addr);
        self.table[at..at + len].copy_from_slice(&value.to_le_bytes()[..len]);
    }

    /// The bytes at `addr..addr + len` (0 past the table's end).
    fn span(&self, addr: u16, len: usize) -> Vec<u8> {
        (usize::from(addr)..usize::from(addr) + len).map(|at| self.table.get(at).copied().unwrap_or(0)).collect()
    }

    /// The size a position takes in its table: 4 bytes on X-series, 2 on the AX.
    fn position_size(&self) -> usize {
        usize::from(self.model.at.position_size)
    }

    /// Moves on toward its goal for `dt`; whether it is still moving.
    fn step(&mut self, dt: Duration) -> bool {
        let at = self.model.at;
        let size = self.position_size();
        if self.table[usize::from(at.torque)] == 0 {
            self.write(at.moving, 0, 1);
            return false;
        }
        let goal = f64::from(self.read(at.goal, size));
        let speed = match self.read(at.speed, size) {
            0 => self.model.top_speed,
            units => (f64::from(units) * at.speed_unit).min(self.model.top_speed),
        };
        let step = speed * dt.as_secs_f64();
        let left = goal - self.at;
        self.at = if left.abs() <= step { goal } else { self.at + step * left.signum() };
        // Within the table's range: a position fits its field.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let present = self.at.round().max(0.0) as u32;
        self.write(at.present, present, size);
        let moving = (goal - self.at).abs() > 0.5;
        self.write(at.moving, u32::from(moving), 1);
        moving
    }
}

/// What the emulated bus did, as its log says it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BusEvent {
    /// A packet it read (any servo's, or none's).
    Heard(Packet),
    /// Bytes that were no packet.
    Skipped {
        /// How many bytes.
        bytes: usize,
        /// Why.
        why: &'static str,
    },
}

impl crate::sim::Received for BusEvent {
    fn received(&self) -> Option<String> {
        match self {
            Self::Heard(packet) => Some(format!("{packet:?}")),
            Self::Skipped { bytes, why } => Some(format!("skipped {bytes} bytes: {why}")),
        }
    }
}

/// The emulated bus.
#[derive(Debug)]
pub struct DynamixelBus {
    servos: Vec<Servo>,
    packets: Packets,
    /// Answers waiting for their return delay: when each is due, and its bytes.
    answers: VecDeque<(Instant, Vec<u8>)>,
    events: VecDeque<BusEvent>,
    /// When the servos last moved on (none: none was moving).
    moved: Option<Instant>,
    /// What happens to the bus, how long after it first hears a packet.
    scheduled: VecDeque<(Duration, BusCommand)>,
    /// When it first heard a packet.
    began: Option<Instant>,
    /// Whether its cable was pulled.
    unplugged: bool,
}

impl DynamixelBus {
    /// A bus of `servos`.
    pub fn new(servos: Vec<Servo>) -> Self {
        Self {
            servos,
            packets: Packets::instructions(),
            answers: VecDeque::new(),
            events: VecDeque::new(),
            moved: None,
            scheduled: VecDeque::new(),
            began: None,
            unplugged: false,
        }
    }

    /// The bus, with `command` carried out `after` it first hears a packet
    /// (`sim --hardware-error 2:overheating@5`), each in the order of its time.
    pub fn scheduling(mut self, after: Duration, command: BusCommand) -> Self {
        let at = self.scheduled.partition_point(|(then, _)| *then <= after);
        self.scheduled.insert(at, (after, command));
        self
    }

    /// What was scheduled and is due by `now`, carried out.
    fn carry_out_scheduled(&mut self, now: Instant) {
        let Some(began) = self.began else { return };
        while self.scheduled.front().is_some_and(|(after, _)| began + *after <= now) {
            if let Some((_, command)) = self.scheduled.pop_front() {
                self.handle_command(now, command);
            }
        }
    }

    /// The demo bus: an XL430 (ID 1) and an XM430 (ID 2) on Protocol 2.0, and an AX-12A (ID 3) on 1.0.
    pub fn demo() -> Self {
        Self::new(vec![Servo::new(&XL430_W250, 1), Servo::new(&XM430_W350, 2), Servo::new(&AX_12A, 3)])
    }

    /// Carries out `packet`: each servo it is for, in its protocol, answers in turn.
    fn carry_out(&mut self, now: Instant, packet: &Packet) {
        let Kind::Instruction(code) = packet.kind else { return };
        let mut due = self.answers.back().map_or(now, |(due, _)| (*due).max(now));
        if code == instruction::SYNC_READ && packet.protocol == Protocol::Two {
            // Each listed servo answers in the order listed.
            let Some((addr, len, ids)) = sync_header(&packet.params) else { return };
            for id in ids.iter() {
                if let Some(servo) =
                    self.servos.iter().find(|servo| servo.id() == *id && servo.model.protocol == Protocol::Two)
                {
                    let data = servo.span(addr, usize::from(len));
                    due += delay(servo);
                    let error = alert(servo);
                    self.answers.push_back((due, Packet::status(Protocol::Two, *id, error, data).to_bytes()));
                }
            }
            return;
        }
        for index in 0..self.servos.len() {
            let servo = &self.servos[index];
            let (id, protocol) = (servo.id(), servo.model.protocol);
            if protocol != packet.protocol || (packet.id != id && packet.id != BROADCAST) {
                continue;
            }
            // The level in force when the packet came (a write that changes it is answered as before).
            let level = servo.read(servo.model.at.status_return, 1);
            let answer = self.answer(index, code, &packet.params);
            let servo = &self.servos[index];
            let asked = match code {
                // A ping is always answered, broadcast or not, whatever the level (the
                // RX-28 and AX-12 manuals' PING: "a Status Packet is always returned").
                instruction::PING => true,
                instruction::READ => packet.id == id && level >= 1,
                _ => packet.id == id && level >= 2,
            };
            if let (true, Some((error, params))) = (asked, answer) {
                due += delay(servo);
                self.answers.push_back((due, Packet::status(protocol, id, error, params).to_bytes()));
            }
        }
    }

    /// What servo `index` does with `code`: its status's error byte and parameters (none: no answer at all).
    fn answer(&mut self, index: usize, code: u8, params: &[u8]) -> Option<(u8, Vec<u8>)> {
        let servo = &mut self.servos[index];
        let two = servo.model.protocol == Protocol::Two;
        let (addr, rest) = match (two, params) {
            (true, [low, high, rest @ ..]) => (u16::from_le_bytes([*low, *high]), rest),
            (false, [addr, rest @ ..]) => (u16::from(*addr), rest),
            _ => (0, params),
        };
        let refused = |two: bool, result: u8, bits: u8| Some((if two { result } else { bits }, Vec::new()));
        match code {
            instruction::PING if two => {
                let mut said = servo.model.number.to_le_bytes().to_vec();
                said.push(servo.model.firmware);
                Some((alert(servo), said))
            }
            instruction::PING => Some((alert(servo), Vec::new())),
            instruction::READ => {
                let len = match (two, rest) {
                    (true, [low, high]) => usize::from(u16::from_le_bytes([*low, *high])),
                    (false, [len]) => usize::from(*len),
                    _ => return refused(two, result::DATA_LENGTH, error_one::INSTRUCTION),
                };
                Some((alert(servo), servo.span(addr, len)))
            }
            instruction::WRITE => {
                let locked = servo.model.at.eeprom_end.is_some_and(|end| addr < end)
                    && servo.table[usize::from(servo.model.at.torque)] != 0;
                if rest.is_empty() || locked || !servo.model.writable(addr, rest.len()) {
                    return refused(two, result::ACCESS, error_one::RANGE);
                }
                let at = usize::from(addr);
                servo.table[at..at + rest.len()].copy_from_slice(rest);
                Some((alert(servo), Vec::new()))
            }
            instruction::SYNC_WRITE => {
                self.sync_write(index, params);
                None
            }
            _ => refused(two, result::INSTRUCTION, error_one::INSTRUCTION),
        }
    }

    /// Servo `index` takes its part of a sync write, if the packet holds one for it.
    fn sync_write(&mut self, index: usize, params: &[u8]) {
        let servo = &mut self.servos[index];
        let two = servo.model.protocol == Protocol::Two;
        let (addr, len, entries) = match (two, params) {
            (true, [a0, a1, l0, l1, entries @ ..]) => {
                (u16::from_le_bytes([*a0, *a1]), usize::from(u16::from_le_bytes([*l0, *l1])), entries)
            }
            (false, [addr, len, entries @ ..]) => (u16::from(*addr), usize::from(*len), entries),
            _ => return,
        };
        let id = servo.id();
        let mine = entries.chunks_exact(len + 1).find(|entry| entry[0] == id);
        if let Some(entry) = mine
            && servo.model.writable(addr, len)
        {
            let at = usize::from(addr);
            servo.table[at..at + len].copy_from_slice(&entry[1..]);
        }
    }
}

/// A 2.0 sync read's address, length and IDs.
fn sync_header(params: &[u8]) -> Option<(u16, u16, Vec<u8>)> {
    let [a0, a1, l0, l1, ids @ ..] = params else { return None };
    Some((u16::from_le_bytes([*a0, *a1]), u16::from_le_bytes([*l0, *l1]), ids.to_vec()))
}

/// How long `servo` waits before it answers: its return delay time, 2 µs a unit.
fn delay(servo: &Servo) -> Duration {
    Duration::from_micros(2 * u64::from(servo.read(servo.model.at.return_delay, 1)))
}

/// A status's error byte for what `servo` suffers: 2.0's alert bit while
/// its hardware error status holds any error; 1.0's error bits themselves.
fn alert(servo: &Servo) -> u8 {
    match servo.model.at.hardware_error {
        Some(addr) if servo.read(addr, 1) != 0 => result::ALERT,
        Some(_) => 0,
        None => servo.errors,
    }
}

/// A hardware error a servo can suffer (the bit it has in 2.0's Hardware
/// Error Status, in 1.0's status error byte and in both's Shutdown field).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fault {
    /// Its input voltage is outside its limits.
    InputVoltage,
    /// It is hotter than its temperature limit.
    Overheating,
    /// It is held against more load than it can move.
    Overload,
}

impl Fault {
    /// The fault named as `sim --hardware-error` names it.
    pub fn named(name: &str) -> Option<Self> {
        match name {
            "input-voltage" => Some(Self::InputVoltage),
            "overheating" => Some(Self::Overheating),
            "overload" => Some(Self::Overload),
            _ => None,
        }
    }

    /// Its bit: the same in 2.0's Hardware Error Status, in 1.0's status
    /// error byte, and in both's Shutdown field.
    fn bit(self) -> u8 {
        match self {
            Self::InputVoltage => 0x01,
            Self::Overheating => 0x04,
            Self::Overload => 0x20,
        }
    }
}

/// What a test or `sim` does to the bus while it runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BusCommand {
    /// Servo `id` suffers `fault`: it says so in every status from now on
    /// and, when its Shutdown field holds the fault, lets its torque go.
    Fault {
        /// The servo.
        id: u8,
        /// What it suffers.
        fault: Fault,
    },
    /// The cable is pulled: the bus closes its link.
    Unplug,
    /// A hand turns servo `id` to `position` (its units): a servo with its
    /// torque off stays there; one with its torque on pulls back to its goal.
    Hand {
        /// The servo.
        id: u8,
        /// Where the hand leaves it.
        position: u32,
    },
}

impl Servo {
    /// Suffers `fault`, as the firmware reports and acts on it.
    fn suffer(&mut self, fault: Fault) {
        let at = self.model.at;
        let bit = fault.bit();
        let shutdown = match at.hardware_error {
            Some(addr) => {
                self.write(addr, self.read(addr, 1) | u32::from(bit), 1);
                self.read(at.shutdown, 1)
            }
            None => {
                self.errors |= bit;
                self.read(at.shutdown, 1)
            }
        };
        if fault == Fault::Overheating {
            // Past its limit: what a controller reads as the cause.
            let limit = self.read(at.temperature_limit, 1);
            self.write(at.temperature, limit + 3, 1);
        }
        if shutdown & u32::from(bit) != 0 {
            self.write(at.torque, 0, 1);
        }
    }
}

impl Driver for DynamixelBus {
    type Command = BusCommand;
    type Event = BusEvent;

    fn handle_command(&mut self, now: Instant, command: BusCommand) {
        match command {
            BusCommand::Fault { id, fault } => {
                if let Some(servo) = self.servos.iter_mut().find(|servo| servo.id() == id) {
                    servo.suffer(fault);
                }
            }
            BusCommand::Unplug => self.unplugged = true,
            BusCommand::Hand { id, position } => {
                if let Some(servo) = self.servos.iter_mut().find(|servo| servo.id() == id) {
                    servo.at = f64::from(position);
                    let (at, size) = (servo.model.at.present, servo.position_size());
                    servo.write(at, position, size);
                    if servo.table[usize::from(servo.model.at.torque)] != 0 {
                        self.moved.get_or_insert(now);
                    }
                }
            }
        }
    }

    fn handle_input(&mut self, now: Instant, bytes: &[u8]) {
        self.began.get_or_insert(now);
        self.carry_out_scheduled(now);
        for read in self.packets.push(bytes) {
            match read {
                Read::Packet(packet) => {
                    self.carry_out(now, &packet);
                    self.events.push_back(BusEvent::Heard(packet));
                }
                Read::Skipped { bytes, why } => self.events.push_back(BusEvent::Skipped { bytes, why }),
            }
        }
        if self.moved.is_none() && self.servos.iter().any(|servo| servo.table[usize::from(servo.model.at.torque)] != 0)
        {
            self.moved = Some(now);
        }
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.carry_out_scheduled(now);
        if let Some(then) = self.moved {
            let dt = now.saturating_duration_since(then);
            // Every servo moves on, whether or not another still moves.
            let mut moving = false;
            for servo in &mut self.servos {
                moving |= servo.step(dt);
            }
            self.moved = moving.then_some(now);
        }
    }

    fn handle_disconnect(&mut self, _reason: &str) {
        self.answers.clear();
    }

    fn poll_transmit(&mut self, now: Instant) -> Option<Vec<u8>> {
        if self.answers.front().is_some_and(|(due, _)| *due <= now) {
            return self.answers.pop_front().map(|(_, bytes)| bytes);
        }
        None
    }

    fn wants_close(&self) -> bool {
        self.unplugged
    }

    fn poll_event(&mut self) -> Option<BusEvent> {
        self.events.pop_front()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        let answer = self.answers.front().map(|(due, _)| *due);
        let motion = self.moved.map(|then| then + MOTION_STEP);
        let scheduled = self.began.zip(self.scheduled.front()).map(|(began, (after, _))| began + *after);
        answer.into_iter().chain(motion).chain(scheduled).min()
    }
}

#[cfg(test)]
mod tests;
