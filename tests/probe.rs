//! The connection doctor (`servo-studio probe`, `device::probe`): each
//! emulator is found as its own family, through the other families' probes;
//! silent and garbage peers are told apart; and no probe request changes any
//! emulator's state.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::{Duration, Instant};

use crate::common::{self, Chatter, peer, sim};
use servo_studio::device::probe::{Identity, ProbeDriver, ProbeOptions, plan, probe_port, requests};
use servo_studio::device::{plen2, rflex, servo};
use servo_studio::link::{Driver, PortName, system_opener};
use servo_studio::project::Family;
use servo_studio::sim::{Plen2Sim, Plen2Timing, RflexSim, RflexSimConfig, ServoSim, SimConfig};

fn probe(port: &str) -> servo_studio::device::probe::ProbeResult {
    probe_port(&PortName::parse(port).unwrap(), &system_opener(), &ProbeOptions::default()).unwrap()
}

/// What `requests` sends to a PLEN2 is what plen2.md §2 lists as getters, and
/// no servo or rFLEX probe holds a byte that begins a PLEN2 command (`$ # > <`):
/// between commands the PLEN2 ignores every other byte (§1).
#[test]
fn the_probes_are_getters_and_foreign_ones_hold_no_plen2_command_byte() {
    assert_eq!(requests(Family::Plen2), [b"<VI".to_vec(), b"<JS".to_vec()]);
    // board.md §1: magic, id 30130 and 10030 little-endian, no content, sum of bytes.
    assert_eq!(
        requests(Family::Servo),
        [
            vec![0x13, 0x4C, 0x05, 0x1D, 0xB2, 0x75, 0x00, 0x00, 0xA8],
            vec![0x13, 0x4C, 0x05, 0x1D, 0x2E, 0x27, 0x00, 0x00, 0xD6],
        ]
    );
    // rflex.md §2: 1B 02, port 1, id 0, opcode 1 SYS_STATUS, no data, XOR checksum, 1B 03.
    assert_eq!(requests(Family::Rflex), [vec![0x1B, 0x02, 0x01, 0x00, 0x01, 0x00, 0x00, 0x1B, 0x03]]);
    for family in [Family::Servo, Family::Rflex] {
        for request in requests(family) {
            assert!(!request.iter().any(|byte| b"$#><".contains(byte)), "{family}: {request:02x?}");
        }
    }
}

/// Runs `sim` in virtual time until `until`, answering nothing back (what it
/// prints is dropped: the probe's reader is not under test here).
fn settle<D: Driver>(sim: &mut D, until: Instant) {
    while let Some(due) = sim.poll_timeout().filter(|due| *due <= until) {
        sim.handle_timeout(due);
        while sim.poll_transmit(due).is_some() {}
    }
    while sim.poll_transmit(until).is_some() {}
}

/// Every family's probe, to a sim, as the doctor sends them (each family's in turn).
fn send_every_probe<D: Driver>(sim: &mut D, t0: Instant) -> Instant {
    let mut now = t0;
    for &family in Family::all() {
        for request in requests(family) {
            sim.handle_input(now, &request);
            now += Duration::from_millis(200);
            settle(sim, now);
        }
    }
    now + Duration::from_secs(1)
}

/// A servo board, a PLEN2 and an rFLEX base each given every family's probe
/// end up exactly as a twin that was sent nothing.
#[test]
fn no_probe_request_changes_any_emulators_state() {
    let t0 = Instant::now();

    let image = common::unauthorable_image();
    let (mut probed, mut twin) =
        (ServoSim::new(SimConfig::default(), image.clone()), ServoSim::new(SimConfig::default(), image));
    let end = send_every_probe(&mut probed, t0);
    settle(&mut twin, end);
    settle(&mut probed, end);
    assert_eq!(probed.image(), twin.image(), "the servo board's memory");
    for id in 0..=32 {
        assert_eq!(probed.angle(id, end), twin.angle(id, end), "servo {id}");
    }

    let (mut probed, mut twin) = (Plen2Sim::new(Plen2Timing::default()), Plen2Sim::new(Plen2Timing::default()));
    let end = send_every_probe(&mut probed, t0);
    settle(&mut twin, end);
    settle(&mut probed, end);
    let (mut after, before) = (probed.state(), twin.state());
    assert_eq!(after.executed, 2, "the PLEN2 ran its own two getters and nothing else: {after:?}");
    assert_eq!((after.dropped, after.lost_bytes), (0, 0), "no foreign byte began a command");
    after.executed = before.executed;
    assert_eq!(after, before, "the PLEN2's joints, settings, slots and queue");

    let (mut probed, mut twin) = (RflexSim::new(RflexSimConfig::default()), RflexSim::new(RflexSimConfig::default()));
    let end = send_every_probe(&mut probed, t0);
    settle(&mut twin, end);
    settle(&mut probed, end);
    let (mut after, before) = (probed.state(), twin.state());
    // The battery drains with the emulator's clock, which only moves when it is called.
    assert!((after.battery_volts - before.battery_volts).abs() < 0.01, "{after:?}");
    after.battery_volts = before.battery_volts;
    assert_eq!(after, before, "the base's brake, motion, pose and sonar");
}

/// The three emulators, each behind the other families' probes (the doctor
/// asks the PLEN2 first, then the servo board, then the base), are named
/// right, with what they say of themselves.
#[test]
fn each_emulator_is_found_as_its_own_family() {
    let servo = sim(&["--protocol", "servo"]);
    let found = probe(&servo.port).found.expect("the servo board answers");
    let said = found.identity.said::<servo::Said>().expect("a servo board's identity");
    assert!(matches!(said, servo::Said { project_id: Some(_), memory: Some((_, Some(_))) }), "{found:?}");
    assert_eq!(found.baud, 115_200);

    let plen2 = sim(&["--protocol", "plen2"]);
    let found = probe(&plen2.port).found.expect("the PLEN2 answers");
    assert_eq!(found.identity, Identity::new(plen2::Said { version: "PLEN2 Cytisus 1.4.2".into() }));
    assert_eq!(found.baud, 2_000_000);
    assert!(found.link.latency.is_some() && found.link.replies == 2, "{:?}", found.link);

    let rflex = sim(&["--protocol", "rflex"]);
    let found = probe(&rflex.port).found.expect("the base answers");
    assert!(matches!(found.identity.said::<rflex::Said>(), Some(rflex::Said { braked: true, .. })), "{found:?}");
    assert_eq!(found.baud, 115_200);

    // A DYNAMIXEL bus: its first 2.0 servo answers the broadcast. The emulator
    // hears at any rate, so the first rate the doctor asks a bus at finds it
    // (a bus heard at one rate only: tests/cli/dynamixel.rs).
    let bus = sim(&["--protocol", "dynamixel"]);
    let found = probe(&bus.port).found.expect("the bus answers");
    assert_eq!(found.identity.to_string(), "DYNAMIXEL XL430-W250, ID 1, Protocol 2.0, firmware 46");
    assert_eq!(found.baud, 115_200);
    // Each family at its own rate, a DYNAMIXEL bus at the rates its servos leave the factory at too.
    let plan: Vec<(u32, Vec<&str>)> =
        plan(None).into_iter().map(|(baud, families)| (baud, families.iter().map(|f| f.tag()).collect())).collect();
    assert_eq!(
        plan,
        [
            (2_000_000, vec!["plen2"]),
            (115_200, vec!["servo", "rflex", "dynamixel"]),
            (57_600, vec!["dynamixel"]),
            (1_000_000, vec!["dynamixel"])
        ]
    );
}

/// Over a Bluetooth-like line the doctor says how the link delivers: late, in
/// clumps or whole — the figures the pacing starts from.
#[test]
fn the_doctor_measures_a_bursty_line() {
    let clumps = sim(&["--protocol", "plen2", "--link", "bursty=15"]);
    let link = probe(&clumps.port).found.unwrap().link;
    assert!(link.latency.unwrap() >= Duration::from_millis(10), "{link:?}");
    assert!(link.clump_gap >= Duration::from_millis(10), "{link:?}");

    let whole = sim(&["--protocol", "plen2", "--link", "bursty=15,whole"]);
    let link = probe(&whole.port).found.unwrap().link;
    assert!(link.whole && link.clump_gap.is_zero(), "{link:?}");
    assert!(link.late >= Duration::from_millis(10), "{link:?}");
    assert!(link.to_string().contains("replies whole"), "{link}");

    // The command line says the same, a line per port, and exits 0.
    let (code, stdout, stderr, _) =
        common::run_in(std::path::Path::new("."), &["probe", "--port", &whole.port], Duration::from_secs(60));
    assert_eq!(code, Some(0), "{stderr}");
    let said = format!("{}: PLEN2 Cytisus 1.4.2 at 2000000 baud; link: first byte after ", whole.port);
    assert!(stdout.starts_with(&said) && stdout.contains("replies whole"), "{stdout}");
}

/// A silent line and a line of noise are told apart, each with what to check,
/// and the command line exits 1 when nothing answered.
#[test]
fn silent_and_garbage_peers_are_named_as_such() {
    let silent = peer(Chatter::Silent);
    let result = probe(&silent.port);
    assert_eq!((result.found.is_none(), result.unrecognised), (true, 0));
    assert!(result.describe(None).contains("nothing answered"), "{}", result.describe(None));

    let noisy = peer(Chatter::Garbage);
    let result = probe(&noisy.port);
    assert!(result.found.is_none(), "{result:?}");
    assert!(result.unrecognised > 0);
    assert!(result.describe(None).contains("in no family's protocol"), "{}", result.describe(None));

    let (code, stdout, stderr, _) = common::run_in(
        std::path::Path::new("."),
        &["probe", "--port", &silent.port, "--timeout-ms", "100"],
        Duration::from_secs(60),
    );
    assert_eq!(code, Some(1), "{stdout}{stderr}");
    assert!(stdout.contains("nothing answered"), "{stdout}");
    assert!(stderr.contains("no board answered"), "{stderr}");
}

/// The probe as a driver, in virtual time: a reply that comes after its
/// request was given up (a slow servo board answering while the base is
/// asked) is still recognised, as the family it is.
#[test]
fn a_late_answer_to_an_earlier_probe_still_names_its_family() {
    let t0 = Instant::now();
    let mut driver = ProbeDriver::new(115_200, &[Family::Servo, Family::Rflex], Duration::from_millis(100));
    let first = driver.poll_transmit(t0).unwrap();
    assert_eq!(first, requests(Family::Servo)[0]);
    driver.handle_written(t0, first.len());
    driver.handle_timeout(driver.poll_timeout().unwrap());
    let second = driver.poll_transmit(t0).unwrap();
    assert_eq!(second, requests(Family::Rflex)[0], "the servo board was given up; the base is asked");
    let reply = servo_studio::protocol::servo::Message::QueryProjectIdResponse { project_id: 7 }.encode().unwrap();
    driver.handle_input(t0 + Duration::from_millis(150), &reply);
    let result = driver.poll_event().unwrap();
    assert_eq!(result.found.unwrap().identity, Identity::new(servo::Said { project_id: Some(7), memory: None }));
    assert!(driver.wants_close());
}
