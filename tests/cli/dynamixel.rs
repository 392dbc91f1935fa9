//! The DYNAMIXEL family on the command line, run as a user runs it: an
//! emulated bus served by `sim` (logged, with a hardware error on a
//! schedule), scanned by `board info` and `export`, refused by `import` with
//! what to do instead; a show of three families with a DYNAMIXEL arm, its
//! motion streamed as the other boards start; and a lost bus stopping it.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss)]

use std::io::{BufRead, BufReader};
use std::process::Command as Process;
use std::time::Duration;

use servo_studio::project::dynamixel::{DynamixelSection, Motion, ServoSetup, Step};
use servo_studio::project::{self, Easing, Family, Project};
use servo_studio::show::family::FamilyCue;
use servo_studio::show::{Cue, Show, Start};

use super::play::{Stage, device, first, logged_until, swinging, waving};
use crate::common;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

/// An arm of an XL430 (ID 1) and an AX-12A (ID 3) holding one motion of `seconds`, a swing there and back.
fn arm(seconds: u32) -> Project {
    let half = seconds * 500;
    let section = DynamixelSection {
        servos: vec![
            ServoSetup { id: 1, name: "肩 shoulder".into(), model_number: 1060, profile: None },
            ServoSetup { id: 3, name: "手".into(), model_number: 12, profile: None },
        ],
        motions: vec![Motion {
            name: "揮手 wave".into(),
            steps: vec![
                Step { duration_ms: half, easing: Easing::EaseInOut, positions: [(1, 2548), (3, 612)].into() },
                Step { duration_ms: half, easing: Easing::Linear, positions: [(1, 2048), (3, 512)].into() },
            ],
        }],
    };
    let mut project = Project::empty(Family::Dynamixel);
    project.sections.set(Family::Dynamixel, section.kept());
    project
}

fn motion_cue(number: f64) -> Start {
    Start::Family(FamilyCue::named("motion", number).unwrap())
}

#[test]
fn board_info_and_export_scan_the_emulated_bus_and_import_says_what_to_do_instead() {
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("bus.log");
    let sim = common::sim(&[
        "--protocol",
        "dynamixel",
        "--log",
        log.to_str().unwrap(),
        "--hardware-error",
        "2:overheating@0",
    ]);
    let info =
        Process::new(EXE).args(["board", "info", "--protocol", "dynamixel", "--port", &sim.port]).output().unwrap();
    let said = String::from_utf8_lossy(&info.stdout);
    assert_eq!(info.status.code(), Some(0), "{}", String::from_utf8_lossy(&info.stderr));
    let lines: Vec<&str> = said.lines().collect();
    assert_eq!(lines.len(), 3, "{said}");
    assert!(
        lines[0].contains("ID   1") && lines[0].contains("XL430-W250") && lines[0].contains("model  1060"),
        "{said}"
    );
    assert!(lines[0].contains("firmware  46") && lines[0].contains("protocol 2.0"), "{said}");
    assert!(lines[0].contains("positions 0..=4095, 72 °C at most"), "{said}");
    assert!(lines[1].contains("XM430-W350") && lines[1].contains("80 °C"), "{said}");
    assert!(lines[2].contains("ID   3") && lines[2].contains("AX-12A") && lines[2].contains("protocol 1.0"), "{said}");
    assert!(lines[2].contains("positions 0..=1023, 70 °C at most"), "{said}");
    // The bus logged what it heard: the broadcast ping first.
    let heard = logged_until(&log, "Instruction(1)", Duration::from_secs(10));
    assert!(heard[0].1.contains("id: 254"), "{heard:?}");

    let out = dir.path().join("found.json");
    let export = Process::new(EXE)
        .args(["export", "--protocol", "dynamixel", "--port", &sim.port, "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(export.status.code(), Some(0), "{}", String::from_utf8_lossy(&export.stderr));
    let exported = project::load(&out).unwrap();
    assert_eq!(exported.family, Family::Dynamixel);
    let kept: Vec<(u8, u16)> =
        DynamixelSection::of(&exported).servos.iter().map(|servo| (servo.id, servo.model_number)).collect();
    assert_eq!(kept, [(1, 1060), (2, 1020), (3, 12)]);

    let import = Process::new(EXE)
        .args(["import", "--protocol", "dynamixel", "--port", &sim.port, "--in", out.to_str().unwrap(), "--yes"])
        .output()
        .unwrap();
    let refused = String::from_utf8_lossy(&import.stderr);
    assert_ne!(import.status.code(), Some(0));
    assert!(
        refused.contains("a DYNAMIXEL stores no motion to import") && refused.contains("Nothing was written"),
        "{refused}"
    );
}

#[test]
fn sim_refuses_a_hardware_error_it_cannot_read_and_a_model_it_does_not_emulate() {
    let wrong = Process::new(EXE)
        .args(["sim", "--protocol", "dynamixel", "--tcp", "127.0.0.1:0", "--hardware-error", "2:melting@1"])
        .output()
        .unwrap();
    assert_ne!(wrong.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&wrong.stderr).contains("write ID:KIND@SECONDS"));
    let dir = tempfile::tempdir().unwrap();
    let state = dir.path().join("mx.json");
    let mut project = Project::empty(Family::Dynamixel);
    let section = DynamixelSection {
        servos: vec![ServoSetup { id: 5, name: String::new(), model_number: 29, profile: None }],
        motions: Vec::new(),
    };
    project.sections.set(Family::Dynamixel, section.kept());
    project::save(&state, &project).unwrap();
    let refused = Process::new(EXE)
        .args(["sim", "--protocol", "dynamixel", "--tcp", "127.0.0.1:0", "--state", state.to_str().unwrap()])
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&refused.stderr);
    assert!(said.contains("servo 5: model 29 is not emulated (use one of XL430-W250 (1060)"), "{said}");
}

#[test]
fn a_dynamixel_arm_plays_its_motion_in_a_show_with_a_servo_board_and_a_plen2() {
    let show = Show {
        devices: vec![device("skull", swinging(2)), device("plen", waving()), device("arm", arm(1))],
        sound: None,
        cues: vec![
            Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(1) },
            Cue { device: "plen".into(), at_ms: 0, start: Start::Slot(2) },
            Cue { device: "arm".into(), at_ms: 0, start: motion_cue(1.0) },
        ],
    };
    let stage = Stage::new(&show, &[]);
    let mut child = stage.play(&[]);
    let stdout = BufReader::new(child.stdout.take().unwrap()).lines().map(Result::unwrap).collect::<Vec<_>>();
    let (code, stderr) = common::ended(child, Duration::from_secs(60));
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains("arm (DYNAMIXEL) answered"), "{stderr}");
    let said = stdout.join("\n");
    assert!(said.contains("arm motion 1 due at"), "{said}");
    // The arm's bus took the motion's frames in as sync writes, started with the servo board's macro.
    let arm = logged_until(stage.log("arm"), "Instruction(131)", Duration::from_secs(10));
    let skull =
        first(&logged_until(stage.log("skull"), "ExecuteMacroRequest", Duration::from_secs(10)), "ExecuteMacroRequest");
    let streamed = first(&arm, "Instruction(131)");
    let apart_ms = (streamed as f64 - skull as f64).abs() / 1e6;
    assert!(apart_ms < 300.0, "the arm and the skull are cued together; {apart_ms:.1} ms apart");
    // A second's motion at 50 frames a second: about 50 sync writes for each protocol.
    let arm = logged_until(stage.log("arm"), "params: [30, 2, 3, 0, 2]", Duration::from_secs(10));
    let frames =
        arm.iter().filter(|(_, said)| said.contains("Instruction(131)") && said.contains("protocol: One")).count();
    assert!((40..=60).contains(&frames), "{frames} frames to the AX-12A");
    eprintln!("figures: |arm − skull| = {apart_ms:.2} ms (cued 0); {frames} frames streamed to the AX-12A");
}

#[test]
fn a_lost_bus_stops_the_show_and_says_which() {
    let show = Show {
        devices: vec![device("skull", swinging(200)), device("arm", arm(60))],
        sound: None,
        cues: vec![
            Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(1) },
            Cue { device: "arm".into(), at_ms: 0, start: motion_cue(1.0) },
        ],
    };
    let mut stage = Stage::new(&show, &[]);
    let child = stage.play(&[]);
    logged_until(stage.log("arm"), "Instruction(131)", Duration::from_secs(30));
    // The U2D2's cable is pulled: the bus goes.
    let index = stage.sims.iter().position(|(name, ..)| name == "arm").unwrap();
    let (_, mut gone, _) = stage.sims.remove(index);
    gone.child.kill().unwrap();
    gone.child.wait().unwrap();
    let (code, stderr) = common::ended(child, Duration::from_secs(30));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("the link to arm was lost") && stderr.contains("every device was stopped"), "{stderr}");
    let skull = logged_until(stage.log("skull"), "SetServoParameterRequest", Duration::from_secs(10));
    assert!(skull.iter().any(|(_, said)| said.contains("is_start: false")), "{skull:?}");
}

/// A Bioloid's RoboPlus file, converted onto its AX-12As' IDs, plays on the
/// emulated AX-12As: the bus takes the motion's frames in and ends on the
/// page's last pose, value for value as the file wrote it.
#[test]
fn a_bioloid_roboplus_file_converted_plays_on_emulated_ax_12s() {
    let dir = tempfile::tempdir().unwrap();
    let mtn =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/interchange/roboplus/walk-as-saved.mtn");
    let converted = dir.path().join("bioloid.json");
    let convert = Process::new(EXE)
        .args(["convert", mtn.to_str().unwrap(), "--to", "dynamixel", "--out", converted.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(convert.status.code(), Some(0), "{}", String::from_utf8_lossy(&convert.stderr));
    let project = project::load(&converted).unwrap();
    let section = DynamixelSection::of(&project);
    let getup = section.motions.iter().position(|motion| motion.name.ends_with("Getup")).unwrap();
    let last = section.motions[getup].steps.last().unwrap().positions.clone();
    // The bus of 18 AX-12As the project lists, and a show that plays Getup on it.
    let show = Show {
        devices: vec![device("bioloid", project)],
        sound: None,
        cues: vec![Cue { device: "bioloid".into(), at_ms: 0, start: motion_cue((getup + 1) as f64) }],
    };
    let stage = Stage::new(&show, &[]);
    let mut child = stage.play(&[]);
    let _ = BufReader::new(child.stdout.take().unwrap()).lines().count();
    let (code, stderr) = common::ended(child, Duration::from_secs(60));
    assert_eq!(code, Some(0), "{stderr}");
    // The last frame: a 1.0 sync write of Goal Position (30), 2 bytes, each ID with its value.
    let mut params = vec![30, 2];
    for (id, value) in &last {
        params.push(*id);
        params.extend(u16::try_from(*value).unwrap().to_le_bytes());
    }
    let wanted = format!("params: {params:?}");
    let heard = logged_until(stage.log("bioloid"), &wanted, Duration::from_secs(10));
    let frames = heard.iter().filter(|(_, said)| said.contains("Instruction(131)")).count();
    let seconds = section.motions[getup].steps.iter().map(|step| f64::from(step.duration_ms)).sum::<f64>() / 1000.0;
    assert!(frames as f64 >= seconds * 40.0, "{frames} frames for a {seconds:.2} s motion");
}

/// A remote drives a DYNAMIXEL arm through `serve`: its motions listed, one
/// played by name, a servo posed by caption (clamped to its range), a drive
/// refused with what to do instead, and STOP ending the stream — the bus's
/// own log shows no frame after the hold while it goes on being read.
#[test]
fn serve_plays_poses_and_stops_a_dynamixel_arm() {
    use servo_studio::sim::MonotonicClock;
    let show = Show {
        devices: vec![device("skull", swinging(400)), device("arm", arm(60))],
        sound: None,
        cues: vec![Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(1) }],
    };
    let stage = Stage::new(&show, &[]);
    let served = super::serve::serve(&stage, &["--listen", "127.0.0.1:0"]);
    let (code, listed) = super::serve::ask("GET", &format!("{}/devices", served.url), None, &[]);
    assert_eq!(code, 200);
    assert_eq!(listed["devices"][1]["motions"][0]["name"], "揮手 wave", "{listed}");
    let (code, said) = super::serve::post(&served, "/devices/arm/play", Some(r#"{"what": "揮手 wave"}"#));
    assert_eq!(code, 200, "{said}");
    logged_until(stage.log("arm"), "Instruction(131)", Duration::from_secs(30));
    let (code, posed) = super::serve::post(&served, "/devices/arm/pose", Some(r#"{"axis": "手", "value": 170}"#));
    assert_eq!(code, 200, "{posed}");
    let deg = posed["value"].as_f64().unwrap();
    assert!((deg - 149.7).abs() < 0.1, "an AX-12A turns to its last position, 149.7°: {posed}");
    let (code, said) =
        super::serve::post(&served, "/devices/arm/drive", Some(r#"{"speed_m_s": 0.1, "turn_deg_s": 0}"#));
    assert_eq!(code, 422, "{said}");
    assert!(said["error"].as_str().unwrap().contains("play what it stores"), "{said}");

    let clock = MonotonicClock::now();
    let stopped_ns = clock.ns(std::time::Instant::now());
    assert_eq!(super::serve::post(&served, "/stop", None).0, 200);
    // Thirty reads of the bus after STOP (about 300 ms of it, on the bus's own log).
    let after = |lines: &[(u128, String)], what: &str| {
        lines.iter().filter(|(ns, said)| *ns > stopped_ns && said.contains(what)).count()
    };
    let deadline = std::time::Instant::now() + Duration::from_secs(30);
    let lines = loop {
        let lines = logged_until(stage.log("arm"), "Instruction(2)", Duration::from_secs(30));
        if after(&lines, "Instruction(2)") >= 30 {
            break lines;
        }
        assert!(std::time::Instant::now() < deadline, "the bus was not read after STOP");
        std::thread::yield_now();
    };
    let writes = after(&lines, "Instruction(131)");
    assert!(writes <= 3, "{writes} sync writes after STOP: the hold (one a protocol), not a stream");
}

/// With no `--baud`, a scan tries the usual rates in turn until servos
/// answer: a pseudo-terminal whose bus (an AX-12A, ID 1) hears only at
/// 1000000 baud, as an AX leaves the factory — read from the line's own
/// settings — is found at that rate, after 57600 went unanswered.
#[cfg(unix)]
#[test]
fn board_info_tries_the_usual_rates_until_the_bus_answers() {
    use serialport::SerialPort;
    use servo_studio::link::Driver;
    use servo_studio::sim::dynamixel::{AX_12A, DynamixelBus, Servo};
    use std::io::{Read, Write};
    let (mut master, slave) = serialport::TTYPort::pair().unwrap();
    let port = slave.name().unwrap();
    master.set_timeout(Duration::from_millis(5)).unwrap();
    let (stop, stopped) = crossbeam_channel::bounded::<()>(0);
    let peer = std::thread::spawn(move || {
        let mut bus = DynamixelBus::new(vec![Servo::new(&AX_12A, 1)]);
        let mut heard = std::collections::BTreeSet::new();
        let mut bytes = [0u8; 512];
        while matches!(stopped.try_recv(), Err(crossbeam_channel::TryRecvError::Empty)) {
            let Ok(count) = master.read(&mut bytes) else { continue };
            let rate = master.baud_rate().unwrap();
            heard.insert(rate);
            if count == 0 || rate != 1_000_000 {
                // At another rate the servo hears only noise.
                continue;
            }
            let now = std::time::Instant::now();
            bus.handle_input(now, &bytes[..count]);
            while let Some(answer) = bus.poll_transmit(now + Duration::from_secs(1)) {
                master.write_all(&answer).unwrap();
            }
        }
        heard
    });
    let info = Process::new(EXE).args(["board", "info", "--protocol", "dynamixel", "--port", &port]).output().unwrap();
    let (said, stderr) = (String::from_utf8_lossy(&info.stdout), String::from_utf8_lossy(&info.stderr));
    assert_eq!(info.status.code(), Some(0), "{stderr}");
    assert!(said.contains("ID   1") && said.contains("AX-12A"), "{said}");
    assert!(stderr.contains("no servo answered at 57600 baud; trying 1000000"), "{stderr}");
    assert!(stderr.contains("1 servo(s) answered at 1000000 baud"), "{stderr}");
    // The connection doctor (the editor's too) finds it at that rate.
    let probe = Process::new(EXE).args(["probe", "--port", &port]).output().unwrap();
    let said = String::from_utf8_lossy(&probe.stdout);
    assert_eq!(probe.status.code(), Some(0), "{said}{}", String::from_utf8_lossy(&probe.stderr));
    assert!(said.contains("DYNAMIXEL servo, ID 1, Protocol 1.0") && said.contains("1000000"), "{said}");
    drop(stop);
    let heard = peer.join().unwrap();
    assert!(heard.contains(&57_600) && heard.contains(&1_000_000), "{heard:?}");
    assert!(!heard.contains(&3_000_000), "a scan stops where the bus answered: {heard:?}");
    drop(slave);
}

/// A device that takes the connection and never answers: the scan says no
/// servo answered, and a show will not start on it, naming it.
#[test]
fn a_silent_device_is_never_taken_for_a_bus() {
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let address = listener.local_addr().unwrap();
    std::thread::spawn(move || {
        // Accepts, reads and says nothing, forever.
        let mut held = Vec::new();
        for stream in listener.incoming() {
            let Ok(mut stream) = stream else { return };
            let mut sink = stream.try_clone().unwrap();
            std::thread::spawn(move || std::io::copy(&mut sink, &mut std::io::sink()));
            held.push(stream.try_clone().unwrap());
            let _ = &mut stream;
        }
    });
    let port = format!("tcp://{address}");
    let info = Process::new(EXE).args(["board", "info", "--protocol", "dynamixel", "--port", &port]).output().unwrap();
    let stderr = String::from_utf8_lossy(&info.stderr);
    assert_ne!(info.status.code(), Some(0));
    assert!(stderr.contains("no servo answered") && stderr.contains("either protocol"), "{stderr}");
    // A show holding an arm there does not start.
    let dir = tempfile::tempdir().unwrap();
    let show = Show { devices: vec![device("arm", arm(1))], sound: None, cues: Vec::new() };
    std::fs::write(dir.path().join("show.json"), show.to_json()).unwrap();
    let play = Process::new(EXE)
        .args(["play", dir.path().join("show.json").to_str().unwrap(), "--device", &format!("arm={port}")])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&play.stderr);
    assert_ne!(play.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("arm") && stderr.contains("servo 1 of its project did not answer"), "{stderr}");
}
