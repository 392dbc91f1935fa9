//! Every robot's own sonars and bumpers (rflex.md §6), end to end: the
//! emulated base, off-centre and turned in its room, measures each
//! transducer's range from its mount along its bearing; `rflex status` and
//! the world map place every echo back on the room's walls. The expected
//! ranges are worked here by intersecting each ray with the four wall
//! segments — not by the emulator's own formula.

#![cfg(unix)]
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::time::{Duration, Instant};

use servo_studio::device::rflex::{Odometry, RflexBase, echo_point};
use servo_studio::link::{PortName, no_waker};
use servo_studio::project::Family;
use servo_studio::protocol::rflex::{ATRV_JR, B21R, Conversion, MAGELLAN};
use servo_studio::sim::{BaseState, RflexSim, RflexSimCommand, RflexSimConfig, spawn_pty};

const ROOM: (f64, f64) = (5.0, 3.6);
const START: (f64, f64, f64) = (0.6, -0.35, 37.0);

fn presets() -> [(&'static str, Conversion); 3] {
    [("b21r", B21R), ("atrv-jr", ATRV_JR), ("magellan", MAGELLAN)]
}

/// A point of the base's frame in the room.
fn in_room(point: [f64; 2]) -> [f64; 2] {
    let (x, y, theta) = (START.0, START.1, START.2.to_radians());
    let (sin, cos) = theta.sin_cos();
    [x + point[0] * cos - point[1] * sin, y + point[0] * sin + point[1] * cos]
}

/// How far a ray from `origin` along `angle` goes before it meets one of the room's four walls.
fn to_wall(origin: [f64; 2], angle: f64) -> f64 {
    let (w, h) = (ROOM.0 / 2.0, ROOM.1 / 2.0);
    let corners = [[-w, -h], [w, -h], [w, h], [-w, h]];
    let d = [angle.cos(), angle.sin()];
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let mut nearest = f64::INFINITY;
    for i in 0..4 {
        let (a, b) = (corners[i], corners[(i + 1) % 4]);
        let edge = [b[0] - a[0], b[1] - a[1]];
        let denominator = cross(d, edge);
        if denominator.abs() < 1e-12 {
            continue;
        }
        let to_a = [a[0] - origin[0], a[1] - origin[1]];
        let t = cross(to_a, edge) / denominator;
        let u = cross(to_a, d) / denominator;
        if t > 0.0 && (-1e-9..=1.0 + 1e-9).contains(&u) {
            nearest = nearest.min(t);
        }
    }
    nearest
}

/// How far `point` is from the nearest wall (it may lie up to `slack` outside the room).
fn off_wall(point: [f64; 2], slack: f64) -> f64 {
    let (w, h) = (ROOM.0 / 2.0, ROOM.1 / 2.0);
    let inside = point[0].abs() <= w + slack && point[1].abs() <= h + slack;
    assert!(inside, "{point:?} is outside the room");
    (w - point[0].abs()).abs().min((h - point[1].abs()).abs())
}

fn config(conversion: Conversion) -> RflexSimConfig {
    RflexSimConfig {
        conversion,
        room_m: ROOM,
        start: (START.0, START.1, START.2.to_radians()),
        ..RflexSimConfig::default()
    }
}

/// An emulated base the test holds.
type Base = servo_studio::sim::SimHandle<RflexSimCommand, servo_studio::sim::RflexSimEvent>;

fn inspect(base: &Base) -> BaseState {
    let (reply, state) = crossbeam_channel::bounded(1);
    base.command(RflexSimCommand::Inspect(reply));
    state.recv_timeout(Duration::from_secs(10)).unwrap()
}

#[test]
fn each_preset_measures_from_its_own_mounts_along_its_own_bearings() {
    for (name, conversion) in presets() {
        let sim = spawn_pty(RflexSim::new(config(conversion)), no_waker()).unwrap();
        let state = inspect(&sim);
        let layout = conversion.layout;
        assert_eq!(state.sonar_m.len(), layout.sonar_count(), "{name}");
        let quantum = 1.0 / layout.raw_per_m;
        let mut echoes = 0;
        for transducer in layout.transducers() {
            let mount = in_room([transducer.mount_m.0, transducer.mount_m.1]);
            let expected = to_wall(mount, START.2.to_radians() + transducer.bearing_rad);
            let limit = 3000.0 * quantum;
            match state.sonar_m[&transducer.id] {
                Some(got) => {
                    assert!(
                        (got - expected).abs() <= 0.01 + quantum,
                        "{name} id {}: {got} vs {expected}",
                        transducer.id
                    );
                    echoes += 1;
                }
                None => assert!(expected > limit - 0.01, "{name} id {}: no echo at {expected} m", transducer.id),
            }
        }
        assert!(echoes * 3 > layout.sonar_count(), "{name}: many transducers hear a wall ({echoes})");
    }
}

#[test]
fn rflex_status_places_every_echo_on_the_rooms_walls() {
    for (name, conversion) in presets() {
        let board = common::sim(&[
            "--protocol",
            "rflex",
            "--tcp",
            "127.0.0.1:0",
            "--robot",
            name,
            "--room",
            "5x3.6",
            "--start",
            "0.6,-0.35,37",
        ]);
        let (code, stdout, stderr, _) = common::run_in(
            std::path::Path::new(env!("CARGO_TARGET_TMPDIR")),
            &["rflex", "status", "--port", &board.port, "--robot", name],
            Duration::from_secs(20),
        );
        assert_eq!(code, Some(0), "{name}: {stderr}");
        let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
        let sonar = report["sonar"].as_array().unwrap();
        assert_eq!(sonar.len(), conversion.layout.sonar_count(), "{name}");
        assert_eq!(report["unknown_sonar"], serde_json::json!([]), "{name}");
        let mut placed = 0;
        for reading in sonar {
            let Some(range) = reading["range_m"].as_f64() else { continue };
            let mount = [reading["mount_m"][0].as_f64().unwrap(), reading["mount_m"][1].as_f64().unwrap()];
            let bearing = reading["bearing_deg"].as_f64().unwrap().to_radians();
            let echo = in_room([mount[0] + range * bearing.cos(), mount[1] + range * bearing.sin()]);
            let off = off_wall(echo, 0.02);
            assert!(off < 0.02, "{name} id {}: {echo:?} is {off} m off a wall", reading["id"]);
            placed += 1;
        }
        assert!(placed > 0, "{name}");
    }
}

/// A client on an in-process emulated base, once it has a full set of reports.
fn complete_set(config: RflexSimConfig) -> (Base, RflexBase) {
    let conversion = config.conversion;
    let sim = spawn_pty(RflexSim::new(config), no_waker()).unwrap();
    let port = PortName::parse(&sim.port_name).unwrap();
    let settings = servo_studio::device::line_settings(Family::Rflex);
    let (wake, woken) = crossbeam_channel::bounded::<()>(1);
    let waker: servo_studio::link::Waker = std::sync::Arc::new(move || {
        let _ = wake.try_send(());
    });
    let mut base = RflexBase::over(servo_studio::link::open(&port, &settings).unwrap(), conversion, waker).unwrap();
    base.start(true);
    let deadline = Instant::now() + Duration::from_secs(10);
    while !base.telemetry.complete() {
        assert!(Instant::now() < deadline, "no full set of reports");
        let _ = base.pump(Instant::now());
        let _ = woken.recv_timeout(Duration::from_millis(100));
    }
    (sim, base)
}

/// For the ROS b21_node (rflex.md §6): a B21r that reports its six body panels only.
#[test]
fn a_b21r_can_report_its_body_panels_only() {
    let (_sim, base) = complete_set(RflexSimConfig { body_panels_only: true, ..config(B21R) });
    assert_eq!(base.telemetry.bumpers.keys().copied().collect::<Vec<_>>(), (0x40..0x46).collect::<Vec<u16>>());
    let (_sim, base) = complete_set(config(B21R));
    assert_eq!(base.telemetry.bumpers.len(), 14, "all fourteen by default");
}

#[test]
fn the_world_maps_echoes_land_on_the_walls_for_every_robot() {
    for (name, conversion) in presets() {
        let (_sim, base) = complete_set(config(conversion));
        let telemetry = &base.telemetry;
        assert!(telemetry.unknown_sonar.is_empty(), "{name}");
        let pose: Odometry = telemetry.pose;
        let mut placed = 0;
        for (&id, range) in &telemetry.sonar_m {
            let Some(range) = range else { continue };
            let transducer = conversion.layout.transducer(id).unwrap();
            let echo = in_room(echo_point(&pose, &transducer, *range));
            assert!(off_wall(echo, 0.02) < 0.02, "{name} id {id}: {echo:?}");
            placed += 1;
        }
        assert!(placed * 3 > conversion.layout.sonar_count(), "{name}: {placed}");
        // The map's cells too: each centre within half a cell's diagonal (and 2 cm) of a wall.
        let cell = 0.05 * std::f64::consts::SQRT_2 / 2.0 + 0.02;
        for (point, _) in telemetry.echoes.points() {
            assert!(off_wall(in_room(point), cell) < cell, "{name}: {point:?}");
        }
    }
}

/// A reading for an id the robot does not have is kept as unknown, never
/// placed on another transducer; a sweep is whole only when every bank the
/// robot has has reported; bumpers follow the robot's style.
#[test]
fn unknown_ids_are_kept_apart_and_a_sweep_needs_every_bank() {
    use servo_studio::device::rflex::{Bump, Telemetry};
    use servo_studio::protocol::rflex::{Report, SonarReading};
    let sonar = |ids: &[u8]| Report::Sonar {
        unknown: 0,
        timestamp: 0,
        readings: ids.iter().map(|&sonar_id| SonarReading { sonar_id, range: 1476 }).collect(),
    };
    let mut telemetry = Telemetry::default();
    telemetry.record(&B21R, 0.0, sonar(&[0, 1, 2, 3, 4]));
    assert_eq!(telemetry.unknown_sonar.keys().copied().collect::<Vec<_>>(), [4], "bank 0 holds four");
    assert_eq!(telemetry.sonar_m.len(), 4);
    assert_eq!(telemetry.echoes.len(), 4, "only the robot's own transducers are placed");
    for bank in 1..13 {
        telemetry.record(&B21R, 0.0, sonar(&[bank * 16]));
        assert!(!telemetry.full_sonar_sweep(), "bank {bank}: 14 banks make a sweep");
    }
    telemetry.record(&B21R, 0.0, sonar(&[13 * 16]));
    assert!(telemetry.full_sonar_sweep());

    let mut magellan = Telemetry::default();
    magellan.record(&MAGELLAN, 0.0, Report::Dio { timestamp: 0, address: 0x41, data: 0b100 });
    magellan.record(&MAGELLAN, 0.0, Report::Dio { timestamp: 0, address: 0x42, data: 0xff });
    assert_eq!(magellan.pressed(), [Bump::Bit { bumper: 10 }], "bumper 8 + bit 2; 0x42 is no bumper");
    assert_eq!(magellan.digital_io.get(&0x42), Some(&0xff));
}
