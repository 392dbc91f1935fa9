//! The rFLEX commands as a user runs them, against the emulated base behind a
//! real pseudo-terminal: drive, status with stuffing and line noise, and a
//! link cut mid-drive.

#![cfg(unix)]
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use common::{Chatter, ended, peer};
use std::io::{Read, Write};
use std::net::{Shutdown, TcpListener, TcpStream};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use servo_studio::link::{LinkEvent, no_waker};
use servo_studio::sim::{
    BaseState, LineNoise, Plen2Sim, Plen2Timing, RflexSim, RflexSimCommand, RflexSimConfig, RflexSimEvent, ServoSim,
    SimConfig, SimHandle, spawn_pty,
};

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

type Base = SimHandle<RflexSimCommand, RflexSimEvent>;

fn base(config: RflexSimConfig) -> Base {
    spawn_pty(RflexSim::new(config), no_waker()).unwrap()
}

fn inspect(base: &Base) -> BaseState {
    let (reply, state) = crossbeam_channel::bounded(1);
    base.command(RflexSimCommand::Inspect(reply));
    state.recv_timeout(Duration::from_secs(10)).unwrap()
}

fn run(args: &[&str]) -> Output {
    Command::new(EXE).args(args).stdin(Stdio::null()).output().unwrap()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn drive_moves_the_base_by_what_its_acceleration_allows_then_stops_and_brakes_it() {
    let base = base(RflexSimConfig::default());
    let began = Instant::now();
    let output =
        run(&["rflex", "drive", "--port", &base.port_name, "--speed", "0.5", "--accel", "0.5", "--seconds", "2"]);
    let took = began.elapsed();
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stderr(&output).contains("stopped, brake set"), "{}", stderr(&output));
    assert!(stderr(&output).contains("m from the start"), "a progress line: {}", stderr(&output));
    let state = inspect(&base);
    assert!(state.braked, "{state:?}");
    assert_eq!(state.speed_m_per_s, 0.0, "stopped");
    // 1 s ramping to 0.5 m/s (0.25 m), then 0.5 m/s for the rest of the 2 s (0.5 m),
    // plus what the stop's ramp-down covers before the brake is set.
    // Bounded by the command's whole run, however slowly this machine ran it.
    let driving = took.as_secs_f64().max(2.0);
    assert!(state.distance_m > 0.72 && state.distance_m < 0.75 + 0.5 * (driving - 2.0) + 0.1, "{state:?} in {took:?}");
    // Re-sent while driving (its 10 Hz cadence is `cargo bench --bench rflex`'s to measure).
    assert!(state.motion_commands >= 5, "re-sent while driving: {}", state.motion_commands);
}

#[test]
fn status_reports_the_emulators_battery_pose_and_sonar_with_noise_and_stuffing_on() {
    let noise: LineNoise = "garbage-every=4,corrupt-every=6,cut-every=9".parse().unwrap();
    let base = base(RflexSimConfig { stuffed: true, noise, ..RflexSimConfig::default() });
    let output = run(&["rflex", "status", "--port", &base.port_name]);
    assert!(output.status.success(), "{}", stderr(&output));
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1, "one JSON object: {stdout}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let state = inspect(&base);
    let volts = report["battery_volts"].as_f64().unwrap();
    assert!((volts - state.battery_volts).abs() < 0.05, "{volts} vs {}", state.battery_volts);
    assert_eq!(report["brake"], serde_json::json!(true));
    for key in ["x_m", "y_m", "theta_rad"] {
        assert_eq!(report[key].as_f64(), Some(0.0), "{key}: a pose from the first report");
    }
    let sonar = report["sonar"].as_array().unwrap();
    assert_eq!(sonar.len(), 48, "a B21r's two rings, a full sweep: {sonar:?}");
    for reading in sonar {
        let id = u8::try_from(reading["id"].as_u64().unwrap()).unwrap();
        let expected = state.sonar_m[&id];
        match (reading["range_m"].as_f64(), expected) {
            (Some(got), Some(want)) => assert!((got - want).abs() < 1e-3, "sonar {id}: {got} vs {want}"),
            (None, None) => {}
            other => panic!("sonar {id}: {other:?}"),
        }
    }
    assert!(sonar.iter().any(|reading| reading["range_m"].is_null()), "corners are out of range");
    assert_eq!(report["unknown_sonar"], serde_json::json!([]));
    assert_eq!(report["bumpers_pressed"], serde_json::json!([]), "at rest");
    assert!(report["checksum_failures"].as_u64().unwrap() > 0, "corrupted reports were counted, not used");
}

/// A cable between the command line (TCP) and the base (its pseudo-terminal)
/// that the test can pull.
fn cable(pty: &str) -> (String, crossbeam_channel::Sender<()>) {
    let (address, pull, _mute) = muting_cable(pty);
    (address, pull)
}

/// A cable that can also be muted: the base's words stop reaching the
/// command line, while the command line's still reach the base.
fn muting_cable(pty: &str) -> (String, crossbeam_channel::Sender<()>, crossbeam_channel::Sender<()>) {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let address = format!("tcp://{}", listener.local_addr().unwrap());
    let mut serial = serialport::new(pty, 115_200).timeout(Duration::from_millis(20)).open().unwrap();
    let (pull, pulled) = crossbeam_channel::bounded::<()>(1);
    let (mute, muted) = crossbeam_channel::bounded::<()>(1);
    std::thread::spawn(move || {
        let mut silent = false;
        let (client, _) = listener.accept().unwrap();
        client.set_read_timeout(Some(Duration::from_millis(20))).unwrap();
        let mut client_reader: TcpStream = client.try_clone().unwrap();
        let mut client_writer = client;
        let mut buffer = [0u8; 512];
        loop {
            if pulled.try_recv().is_ok() {
                let _ = client_writer.shutdown(Shutdown::Both);
                return; // the serial port closes here too
            }
            match client_reader.read(&mut buffer) {
                Ok(0) => return,
                Ok(n) => serial.write_all(&buffer[..n]).unwrap(),
                Err(_) => {}
            }
            silent |= muted.try_recv().is_ok();
            if let Ok(n) = serial.read(&mut buffer)
                && n > 0
                && !silent
                && client_writer.write_all(&buffer[..n]).is_err()
            {
                return;
            }
        }
    });
    (address, pull, mute)
}

#[test]
fn a_link_cut_mid_drive_ends_the_command_at_once_and_the_base_stops_by_its_dead_man() {
    let base = base(RflexSimConfig::default());
    let (address, pull) = cable(&base.port_name);
    let mut child = driving(&base, &address);
    let mut message = child.stderr.take().unwrap();
    let (exited_tx, exited) = crossbeam_channel::bounded(1);
    std::thread::spawn(move || {
        let _ = exited_tx.send(child.wait().unwrap());
    });
    pull.send(()).unwrap();
    // It ends on the cut, not on its 20 s drive: a generous limit tells a hang apart.
    let status = exited.recv_timeout(Duration::from_secs(10)).expect("the command line ends on the cut");
    assert!(!status.success());
    let mut text = String::new();
    message.read_to_string(&mut text).unwrap();
    assert!(text.contains("the link to the base was lost"), "{text}");
    // Nobody sends motion commands now: the dead-man stops the base.
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        match base.events().recv_deadline(deadline) {
            Ok(LinkEvent::Driver(RflexSimEvent::DeadManStop)) => break,
            Ok(_) => {}
            Err(_) => panic!("the dead-man never stopped the base"),
        }
    }
    let state = inspect(&base);
    assert_eq!(state.target_speed_m_per_s, 0.0, "it ramps down to a stop: {state:?}");
    assert!(!state.braked, "the brake was never set: the dead-man alone stopped it");
}

/// Starts `rflex drive` for a long drive and waits until the base is moving.
fn driving(base: &Base, port: &str) -> std::process::Child {
    let child = Command::new(EXE)
        .args(["rflex", "drive", "--port", port, "--speed", "0.4", "--seconds", "20"])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut motion = 0;
    while motion < 5 {
        match base.events().recv_deadline(deadline) {
            Ok(LinkEvent::Driver(RflexSimEvent::Received(servo_studio::protocol::rflex::Command::AxisSetDir {
                ..
            }))) => motion += 1,
            Ok(_) => {}
            Err(_) => panic!("the base never got a motion command"),
        }
    }
    child
}

#[test]
fn a_signal_during_a_drive_stops_the_base_and_sets_its_brake_before_the_command_exits() {
    for (signal, code) in [("INT", 130), ("TERM", 143), ("HUP", 129)] {
        let base = base(RflexSimConfig::default());
        let child = driving(&base, &base.port_name);
        let killed = Command::new("kill").args(["-s", signal, &child.id().to_string()]).status().unwrap();
        assert!(killed.success());
        let (status, text) = ended(child, Duration::from_secs(10));
        assert_eq!(status, Some(code), "SIG{signal}: {text}");
        assert!(text.contains(&format!("interrupted by SIG{signal}")), "{text}");
        assert!(text.contains("the base stopped and its brake is set"), "{text}");
        // The command waited for the base to confirm: by the time it exited, the base had braked.
        let state = inspect(&base);
        assert!(state.braked, "SIG{signal}: {state:?}");
        assert_eq!(state.target_speed_m_per_s, 0.0, "SIG{signal}: {state:?}");
        assert_eq!(state.speed_m_per_s, 0.0, "SIG{signal}: {state:?}");
    }
}

#[test]
fn drive_never_starts_against_a_device_that_does_not_answer_as_a_base() {
    let silent = peer(Chatter::Silent);
    let garbage = peer(Chatter::Garbage);
    let servo_board = spawn_pty(ServoSim::new(SimConfig::default(), Default::default()), no_waker()).unwrap();
    let plen2 = spawn_pty(Plen2Sim::new(Plen2Timing::default()), no_waker()).unwrap();
    let cases = [
        (&silent.port, "did not answer the start-up within 1000 ms"),
        (&garbage.port, "not in the rFLEX protocol"),
        (&servo_board.port_name, "did not answer the start-up within 1000 ms"),
        (&plen2.port_name, "did not answer the start-up within 1000 ms"),
    ];
    for (port, expected) in cases {
        let child = Command::new(EXE)
            .args(["rflex", "drive", "--port", port, "--speed", "0.3", "--seconds", "10"])
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // A 10 s drive asked: it must end on the refusal, long before.
        let (status, text) = ended(child, Duration::from_secs(10));
        assert_eq!(status, Some(1), "{port}: {text}");
        assert!(text.contains(expected), "{port}: {text}");
        assert!(text.contains("nothing was driven"), "{port}: {text}");
        assert!(!text.contains("stopped, brake set"), "no success claimed: {text}");
    }
}

#[test]
fn a_base_that_stops_answering_mid_drive_ends_the_command_at_once_with_a_stop_sent() {
    let base = base(RflexSimConfig::default());
    let (address, _pull, mute) = muting_cable(&base.port_name);
    let child = driving(&base, &address);
    mute.send(()).unwrap();
    // A 20 s drive: it ends on the silence (a second of it, one more for a confirmation), not then.
    let (status, text) = ended(child, Duration::from_secs(15));
    assert_eq!(status, Some(1), "{text}");
    assert!(text.contains("the base stopped answering"), "{text}");
    assert!(text.contains("a stop was sent"), "{text}");
    assert!(text.contains("did not confirm"), "its reports never came back: {text}");
    assert!(!text.contains("stopped, brake set"), "{text}");
    let state = inspect(&base);
    assert_eq!(state.target_speed_m_per_s, 0.0, "told to stop: {state:?}");
    assert!(state.braked, "and to brake: {state:?}");
}

#[test]
fn a_speed_beyond_the_robots_limit_is_refused_before_anything_is_sent() {
    let base = base(RflexSimConfig::default());
    for (flag, value, words) in [("--speed", "2.5", "faster than the b21r's limit of 1 m/s"), ("--turn", "-4", "rad/s")]
    {
        let mut args = vec!["rflex", "drive", "--port", &base.port_name, "--seconds", "1"];
        if flag == "--turn" {
            args.extend(["--speed", "0.1"]);
        }
        args.extend([flag, value]);
        let output = run(&args);
        assert_eq!(output.status.code(), Some(1));
        assert!(stderr(&output).contains(words), "{}", stderr(&output));
        assert!(stderr(&output).contains("nothing was sent"), "{}", stderr(&output));
    }
    // A barrier: a status request of the test's own, through the same line,
    // after anything the refused commands could have sent. Once the base has
    // read it, it has read all of that.
    use servo_studio::protocol::rflex::Command as RflexCommand;
    let mut line = serialport::new(&base.port_name, 115_200).timeout(Duration::from_millis(50)).open().unwrap();
    line.write_all(&RflexCommand::SystemStatus.to_frame().to_bytes().unwrap()).unwrap();
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut received = Vec::new();
    while received.last() != Some(&RflexCommand::SystemStatus) {
        let event = base.events().recv_deadline(deadline).expect("the base read the barrier");
        if let LinkEvent::Driver(RflexSimEvent::Received(command)) = event {
            received.push(command);
        }
    }
    assert_eq!(received, [RflexCommand::SystemStatus], "nothing before the barrier");
    assert_eq!(inspect(&base).motion_commands, 0);
}
