//! The driver against the emulated bus, in fake time: both state machines
//! stepped together, bytes carried between them whole.

use std::time::{Duration, Instant};

use super::*;
use crate::link::Driver;
use crate::sim::dynamixel::{BusCommand, Fault as DynamixelFault};

/// The driver and the emulated bus on one wire, in fake time.
struct Wire {
    driver: DynamixelDriver,
    bus: crate::sim::dynamixel::DynamixelBus,
    now: Instant,
    events: Vec<DynamixelEvent>,
    /// Every packet the driver sent, as bytes.
    sent: Vec<Vec<u8>>,
    /// Whether the bus answers.
    answering: bool,
}

impl Wire {
    fn new() -> Self {
        Self {
            driver: DynamixelDriver::default(),
            bus: crate::sim::dynamixel::DynamixelBus::demo(),
            now: Instant::now(),
            events: Vec::new(),
            sent: Vec::new(),
            answering: true,
        }
    }

    fn ask(&mut self, command: DynamixelCommand) {
        self.driver.handle_command(self.now, command);
        self.carry();
    }

    /// Carries what is waiting on either side to the other.
    fn carry(&mut self) {
        loop {
            let mut moved = false;
            while let Some(bytes) = self.driver.poll_transmit(self.now) {
                self.bus.handle_input(self.now, &bytes);
                self.sent.push(bytes);
                moved = true;
            }
            while let Some(bytes) = self.bus.poll_transmit(self.now) {
                if self.answering {
                    self.driver.handle_input(self.now, &bytes);
                }
                moved = true;
            }
            self.events.extend(std::iter::from_fn(|| self.driver.poll_event()));
            while self.bus.poll_event().is_some() {}
            if !moved {
                return;
            }
        }
    }

    /// Runs for `span` of fake time, each side's timeouts met as they fall due.
    fn run(&mut self, span: Duration) {
        let end = self.now + span;
        while self.now < end {
            let due = [self.driver.poll_timeout(), self.bus.poll_timeout()].into_iter().flatten().min();
            let next = due.map_or(end, |due| due.max(self.now + Duration::from_micros(100))).min(end);
            self.now = next;
            self.bus.handle_timeout(self.now);
            self.driver.handle_timeout(self.now);
            self.carry();
        }
    }

    fn scanned(&mut self) {
        self.ask(DynamixelCommand::Scan { one: 0..=10 });
        self.run(Duration::from_secs(2));
    }

    fn last_reading(&self, id: u8) -> Option<Reading> {
        self.events.iter().rev().find_map(|event| match event {
            DynamixelEvent::Reading { id: of, reading } if *of == id => Some(*reading),
            _ => None,
        })
    }
}

#[test]
fn a_scan_finds_each_servo_with_its_model_firmware_and_limits_in_both_protocols() {
    let mut wire = Wire::new();
    wire.scanned();
    let found: Vec<(u8, Protocol, String, u8)> = wire
        .events
        .iter()
        .filter_map(|event| match event {
            DynamixelEvent::Found(found) => Some((found.id, found.protocol, found.model_name(), found.firmware)),
            _ => None,
        })
        .collect();
    assert_eq!(
        found,
        [
            (1, Protocol::Two, "XL430-W250".to_string(), 46),
            (2, Protocol::Two, "XM430-W350".to_string(), 46),
            (3, Protocol::One, "AX-12A".to_string(), 24)
        ]
    );
    assert!(wire.events.contains(&DynamixelEvent::Scanned { found: 3 }));
    assert!(wire.events.contains(&DynamixelEvent::Scanning { done: 11, of: 11 }), "progress to the last ID");
    let limits: Vec<(u8, Limits)> = wire
        .events
        .iter()
        .filter_map(|event| match event {
            DynamixelEvent::Limits { id, limits } => Some((*id, *limits)),
            _ => None,
        })
        .collect();
    assert_eq!(
        limits,
        [
            (1, Limits { lowest: 0, highest: 4095, temperature_limit_c: 72 }),
            (2, Limits { lowest: 0, highest: 4095, temperature_limit_c: 80 }),
            (3, Limits { lowest: 0, highest: 1023, temperature_limit_c: 70 }),
        ]
    );
    // Each found servo is read at 50 Hz from then on.
    let reading = wire.last_reading(3).unwrap();
    assert_eq!((reading.position, reading.volts, reading.temperature_c), (512, 12.0, 32));
    let readings =
        |wire: &Wire| wire.events.iter().filter(|event| matches!(event, DynamixelEvent::Reading { id: 1, .. })).count();
    let before = readings(&wire);
    wire.run(Duration::from_secs(1));
    assert!((48..=51).contains(&(readings(&wire) - before)), "{} readings in a second", readings(&wire) - before);
}

#[test]
fn goals_are_coalesced_into_one_sync_write_for_each_protocol_and_reached() {
    let mut wire = Wire::new();
    wire.scanned();
    wire.ask(DynamixelCommand::Torque { id: None, on: true });
    wire.run(Duration::from_millis(100));
    // Goals that come before the bus is free go together, a servo's newest only.
    wire.driver.handle_command(wire.now, DynamixelCommand::Read(false));
    wire.run(Duration::from_millis(100));
    wire.sent.clear();
    for position in [2100, 2200, 2300] {
        wire.driver.handle_command(wire.now, DynamixelCommand::Goal { id: 1, position });
    }
    wire.driver.handle_command(wire.now, DynamixelCommand::Goal { id: 2, position: 1000 });
    wire.driver.handle_command(wire.now, DynamixelCommand::Goal { id: 3, position: 700 });
    wire.carry();
    let mut reader = crate::protocol::dynamixel::Packets::instructions();
    let packets: Vec<_> = wire.sent.iter().flat_map(|bytes| reader.push(bytes)).collect();
    use crate::protocol::dynamixel::{Packet, Read, instruction};
    let two = Packet::instruction(
        Protocol::Two,
        0xFE,
        instruction::SYNC_WRITE,
        vec![116, 0, 4, 0, 1, 0xFC, 0x08, 0, 0, 2, 0xE8, 0x03, 0, 0],
    );
    let one = Packet::instruction(Protocol::One, 0xFE, instruction::SYNC_WRITE, vec![30, 2, 3, 0xBC, 0x02]);
    assert_eq!(packets, [Read::Packet(two), Read::Packet(one)], "2300 for servo 1 only");
    wire.ask(DynamixelCommand::Read(true));
    wire.run(Duration::from_secs(3));
    assert_eq!(wire.last_reading(1).unwrap().position, 2300);
    assert_eq!(wire.last_reading(2).unwrap().position, 1000);
    assert_eq!(wire.last_reading(3).unwrap().position, 700);
}

#[test]
fn a_servo_turned_by_hand_with_its_torque_off_reads_where_the_hand_left_it_and_stop_holds_it_there() {
    let mut wire = Wire::new();
    wire.scanned();
    wire.ask(DynamixelCommand::Torque { id: Some(1), on: false });
    wire.bus.handle_command(wire.now, BusCommand::Hand { id: 1, position: 3000 });
    wire.run(Duration::from_millis(100));
    assert_eq!(wire.last_reading(1).unwrap().position, 3000);
    // STOP: the goal becomes where it is, so torque on does not make it jump back.
    wire.ask(DynamixelCommand::Hold);
    wire.ask(DynamixelCommand::Torque { id: Some(1), on: true });
    wire.run(Duration::from_millis(500));
    assert_eq!(wire.last_reading(1).unwrap().position, 3000);
}

#[test]
fn an_overheating_servo_says_so_in_its_readings_and_a_refused_write_is_said() {
    let mut wire = Wire::new();
    wire.scanned();
    wire.bus.handle_command(wire.now, BusCommand::Fault { id: 2, fault: DynamixelFault::Overheating });
    wire.bus.handle_command(wire.now, BusCommand::Fault { id: 3, fault: DynamixelFault::Overload });
    wire.run(Duration::from_millis(200));
    let xm = wire.last_reading(2).unwrap();
    assert_eq!(xm.hardware_error, 0x04, "the cause read from Hardware Error Status");
    assert_eq!(xm.temperature_c, 83, "past its 80 °C limit");
    assert_eq!(wire.last_reading(3).unwrap().hardware_error, 0x20, "1.0: the error byte's overload bit");
    assert_eq!(wire.last_reading(1).unwrap().hardware_error, 0);
    // The X-series refuses a profile write? No: it refuses an EEPROM write with the torque on; the LED is RAM.
    wire.ask(DynamixelCommand::Led { id: 1, on: true });
    wire.run(Duration::from_millis(50));
    assert!(!wire.events.iter().any(|event| matches!(event, DynamixelEvent::Refused { .. })));
}

#[test]
fn a_bus_that_stops_answering_is_said_silent_servo_by_servo_and_again_when_it_answers() {
    let mut wire = Wire::new();
    wire.scanned();
    wire.answering = false;
    wire.run(Duration::from_millis(200));
    assert!(!wire.events.iter().any(|event| matches!(event, DynamixelEvent::Silent { .. })), "not before 300 ms");
    wire.run(Duration::from_millis(400));
    let silent: Vec<u8> = wire
        .events
        .iter()
        .filter_map(|event| match event {
            DynamixelEvent::Silent { id } => Some(*id),
            _ => None,
        })
        .collect();
    assert_eq!(silent, [1, 2, 3], "each servo said once");
    wire.answering = true;
    wire.run(Duration::from_millis(200));
    assert!(wire.events.contains(&DynamixelEvent::Answering { id: 2 }));
}

/// A stream's frames go out on their own clock, 50 a second, each a sync
/// write, and the servos follow; STOP ends it where the servos are.
#[test]
fn a_stream_sends_each_frame_on_its_own_clock_and_stop_ends_it() {
    let mut wire = Wire::new();
    wire.scanned();
    wire.ask(DynamixelCommand::Torque { id: None, on: true });
    wire.run(Duration::from_millis(50));
    let frames: Vec<Vec<(u8, u32)>> = (0..=50).map(|k| vec![(1, 2048 + k * 10), (3, 512 + k)]).collect();
    let every = Duration::from_millis(20);
    let started = wire.now;
    wire.sent.clear();
    wire.ask(DynamixelCommand::Stream { frames: frames.clone(), every });
    wire.run(Duration::from_millis(1100));
    let mut reader = crate::protocol::dynamixel::Packets::instructions();
    let syncs = wire
        .sent
        .iter()
        .flat_map(|bytes| reader.push(bytes))
        .filter(|read| {
            matches!(read, crate::protocol::dynamixel::Read::Packet(packet)
                if packet.kind == crate::protocol::dynamixel::Kind::Instruction(0x83) && packet.protocol == Protocol::Two)
        })
        .count();
    assert_eq!(syncs, 51, "one sync write a frame");
    assert!(wire.events.contains(&DynamixelEvent::Streamed));
    assert_eq!(wire.last_reading(1).unwrap().position, 2548);
    assert_eq!(wire.last_reading(3).unwrap().position, 562);
    assert!(wire.now - started >= Duration::from_secs(1));

    // A second stream stopped half way: the servos stay where they were.
    let back: Vec<Vec<(u8, u32)>> = (0..=50).map(|k| vec![(1, 2548 - k * 10)]).collect();
    wire.ask(DynamixelCommand::Stream { frames: back, every });
    wire.run(Duration::from_millis(500));
    wire.ask(DynamixelCommand::Hold);
    wire.run(Duration::from_millis(100));
    let held = wire.last_reading(1).unwrap().position;
    wire.run(Duration::from_millis(700));
    assert_eq!(wire.last_reading(1).unwrap().position, held, "held, not played on");
    assert!((2250..=2350).contains(&held), "{held}");
}

/// A live move goes at the servo's own profile; a stream takes the profile
/// off (its frames are the motion) and puts it back when it ends.
#[test]
fn a_live_move_keeps_to_the_servos_profile_and_a_stream_lifts_it_while_it_plays() {
    use crate::protocol::dynamixel::{Kind, Packets, Read};
    let mut wire = Wire::new();
    wire.scanned();
    wire.ask(DynamixelCommand::Profile { id: 1, velocity: 100, acceleration: 20 });
    wire.ask(DynamixelCommand::Torque { id: None, on: true });
    wire.run(Duration::from_millis(50));
    wire.ask(DynamixelCommand::Goal { id: 1, position: 3072 });
    wire.run(Duration::from_millis(200));
    // 100 units of 0.229 rev/min: about 1563 position units a second.
    let moved = wire.last_reading(1).unwrap().position - 2048;
    assert!((250..=340).contains(&moved), "{moved} units in 200 ms at its profile");
    wire.run(Duration::from_secs(1));
    assert_eq!(wire.last_reading(1).unwrap().position, 3072);

    wire.sent.clear();
    let frames: Vec<Vec<(u8, u32)>> = (0..=10).map(|k| vec![(1, 3072 - k * 50)]).collect();
    wire.ask(DynamixelCommand::Stream { frames, every: Duration::from_millis(20) });
    wire.run(Duration::from_millis(400));
    let mut reader = Packets::instructions();
    // Each write of Profile Velocity (112) to servo 1: its value.
    let velocities: Vec<u32> = wire
        .sent
        .iter()
        .flat_map(|bytes| reader.push(bytes))
        .filter_map(|read| match read {
            Read::Packet(packet)
                if packet.kind == Kind::Instruction(0x03) && packet.id == 1 && packet.params[..2] == [112, 0] =>
            {
                Some(u32::from_le_bytes(packet.params[2..6].try_into().unwrap()))
            }
            _ => None,
        })
        .collect();
    assert_eq!(velocities, [0, 100], "off while it streams, back when it ends");
    assert_eq!(wire.last_reading(1).unwrap().position, 2572, "the frames followed, not slowed");
}
