//! `servo-studio rflex teleop` against the emulated base, fed through a named
//! pipe of Linux `input_event` records written by the test (the real reading
//! code, as a remote stick forwarded over a pipe would be read): the base
//! drives only while the dead-man is held, and stops — its own state says so —
//! on the dead-man released, the stick centred, a SYN_DROPPED, and the end of
//! the pipe, after which the brake is set and the command exits 1. How soon is
//! measured by `cargo bench --bench rflex` (a test's verdict never depends on
//! this machine's speed).

#![cfg(unix)]
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::io::Write;
use std::path::PathBuf;
use std::process::{Child, Command as Process};
use std::time::{Duration, Instant};

use servo_studio::gamepad::{ABS_RX, ABS_X, ABS_Y, BTN_SOUTH, BTN_TL, BTN_TR, RawEvent};
use servo_studio::link::{LinkEvent, no_waker};
use servo_studio::protocol::rflex::Command;
use servo_studio::sim::{BaseState, RflexSim, RflexSimCommand, RflexSimConfig, RflexSimEvent, SimHandle, spawn_pty};

type Base = SimHandle<RflexSimCommand, RflexSimEvent>;

/// How long anything is waited for before the test calls it hung (a healthy
/// run takes milliseconds: `cargo bench --bench rflex` measures how many).
const HUNG: Duration = Duration::from_secs(10);

struct Rig {
    base: Base,
    teleop: Option<Child>,
    pipe: Option<std::fs::File>,
    _folder: tempfile::TempDir,
    /// Every command the base received, in order.
    received: Vec<Command>,
}

impl Rig {
    /// The emulated base on a pseudo-terminal, `rflex teleop` reading a named
    /// pipe the test writes, and the base's start-up done (its brake released).
    fn start() -> Self {
        Self::with(&[])
    }

    /// As [`Rig::start`], with more options for `rflex teleop`.
    fn with(extra: &[&str]) -> Self {
        let base = spawn_pty(RflexSim::new(RflexSimConfig::default()), no_waker()).unwrap();
        let folder = tempfile::tempdir().unwrap();
        let fifo: PathBuf = folder.path().join("pad");
        assert!(Process::new("mkfifo").arg(&fifo).status().unwrap().success());
        let mut args = vec![
            "rflex",
            "teleop",
            "--port",
            &base.port_name,
            "--gamepad",
            fifo.to_str().unwrap(),
            "--speed",
            "0.4",
            "--turn",
            "1.0",
        ];
        args.extend_from_slice(extra);
        let teleop = common::spawn_quiet(&args);
        // Opening a pipe for writing waits for its reader: the command has started reading.
        let pipe = std::fs::OpenOptions::new().write(true).open(&fifo).unwrap();
        let mut rig = Self { base, teleop: Some(teleop), pipe: Some(pipe), _folder: folder, received: Vec::new() };
        rig.until("the brake released", Duration::from_secs(10), |command, _| *command == Command::BrakeRelease);
        rig
    }

    fn state(&self) -> BaseState {
        let (reply, state) = crossbeam_channel::bounded(1);
        self.base.command(RflexSimCommand::Inspect(reply));
        state.recv_timeout(Duration::from_secs(10)).unwrap()
    }

    /// Writes one frame of events (its SYN_REPORT added) to the pipe; returns when it was written.
    fn frame(&mut self, events: &[RawEvent]) -> Instant {
        let mut bytes: Vec<u8> = events.iter().flat_map(|event| event.to_bytes(0)).collect();
        bytes.extend(RawEvent::report().to_bytes(0));
        self.raw(&bytes)
    }

    fn raw(&mut self, bytes: &[u8]) -> Instant {
        let pipe = self.pipe.as_mut().unwrap();
        pipe.write_all(bytes).unwrap();
        pipe.flush().unwrap();
        Instant::now()
    }

    /// Waits until the base receives a command for which `done` holds (given
    /// the base's state right after it); returns how long that took.
    fn until(&mut self, what: &str, within: Duration, done: impl Fn(&Command, &BaseState) -> bool) -> Duration {
        let began = Instant::now();
        loop {
            let left = (began + within).saturating_duration_since(Instant::now());
            let event = self.base.events().recv_timeout(left).unwrap_or_else(|_| panic!("no {what} within {within:?}"));
            if let LinkEvent::Driver(RflexSimEvent::Received(command)) = event {
                let state = self.state();
                let took = began.elapsed();
                self.received.push(command.clone());
                if done(&command, &state) {
                    return took;
                }
            }
        }
    }

    /// Writes `events` as one frame and waits for the stop they must cause.
    fn stops(&mut self, what: &str, events: &[RawEvent]) -> Duration {
        self.frame(events);
        self.stopped(what)
    }

    fn stopped(&mut self, what: &str) -> Duration {
        // How soon is the benchmark's to measure; here, that the stop comes.
        self.until(what, HUNG, |command, state| {
            matches!(command, Command::AxisSetDir { .. }) && state.target_speed_m_per_s == 0.0
        })
    }

    /// Writes `events` as one frame and waits for the base to be driven forward.
    fn drives(&mut self, what: &str, events: &[RawEvent]) {
        self.frame(events);
        self.until(what, HUNG, |command, state| {
            matches!(command, Command::AxisSetDir { .. }) && (state.target_speed_m_per_s - 0.4).abs() < 0.01
        });
    }
}

impl Drop for Rig {
    fn drop(&mut self) {
        if let Some(mut child) = self.teleop.take() {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

/// Full up on the left stick, the dead-man held.
fn forward() -> Vec<RawEvent> {
    vec![RawEvent::key(BTN_TL, true), RawEvent::abs(ABS_Y, -32768), RawEvent::abs(ABS_X, 0)]
}

#[test]
fn the_base_drives_only_while_the_dead_man_is_held_and_every_cause_stops_it() {
    let mut rig = Rig::start();
    let start_up = rig.received.len();

    // Whatever the sticks and the other buttons do, without the dead-man nothing moves.
    let mut seed = 0x1234_5678_u32;
    let mut random = move || {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        seed
    };
    for _ in 0..300 {
        let value = i32::try_from(random() % 65_536).unwrap() - 32_768;
        let code = [ABS_X, ABS_Y, ABS_RX][usize::try_from(random() % 3).unwrap()];
        let press = random() % 2 == 0;
        rig.frame(&[RawEvent::abs(code, value), RawEvent::key(BTN_SOUTH, press)]);
    }
    // The pipe is read in order: the first command the base gets after these is the dead-man's.
    rig.drives("a drive once the dead-man is held", &forward());
    let motion: Vec<&Command> =
        rig.received[start_up..].iter().filter(|command| matches!(command, Command::AxisSetDir { .. })).collect();
    assert_eq!(motion.len(), 1, "no motion command before the dead-man: {motion:?}");

    // Held still: the base's driver re-sends the velocity on its own (its
    // 10 Hz cadence is the benchmark's to measure), no pad event needed.
    for resend in 1..=3 {
        rig.until(
            &format!("re-sent drive {resend}"),
            HUNG,
            |command, _| matches!(command, Command::AxisSetDir { axis: 0, speed, .. } if *speed > 0),
        );
    }

    // Released: stopped at once.
    let released = rig.stops("the stop on release", &[RawEvent::key(BTN_TL, false)]);
    // Centred with the dead-man still held.
    rig.drives("a drive", &forward());
    let centred = rig.stops("the stop on centring", &[RawEvent::abs(ABS_Y, 200)]);
    // Events dropped: stopped, and a dead-man "still held" in the torn frame does not drive again.
    rig.drives("a drive", &forward());
    rig.raw(&RawEvent::dropped().to_bytes(0));
    let dropped = rig.stopped("the stop on SYN_DROPPED");
    rig.frame(&[RawEvent::abs(ABS_Y, -32768)]);
    rig.frame(&[RawEvent::abs(ABS_Y, -32000)]);
    rig.drives("a drive only once the dead-man is pressed again", &forward());
    let after_drop: Vec<&Command> = rig.received.iter().rev().take(2).collect();
    assert!(after_drop.iter().all(|command| matches!(command, Command::AxisSetDir { .. })), "{after_drop:?}");

    // The pipe ends: stopped, braked, and the command exits 1 saying why.
    rig.pipe = None;
    let ended = rig.stopped("the stop at the end of the pipe");
    rig.until("the brake set", HUNG, |command, _| *command == Command::BrakeSet);
    assert!(rig.state().braked);
    let (code, stderr) = common::ended(rig.teleop.take().unwrap(), Duration::from_secs(10));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("the gamepad's input ended (end of file); the base was stopped and its brake set"),
        "{stderr}"
    );
    eprintln!(
        "stopped after: release {released:?}, centring {centred:?}, SYN_DROPPED {dropped:?}, end of file {ended:?}"
    );
}

#[test]
fn a_gamepad_that_cannot_be_opened_stops_nothing_it_never_drove_and_exits_1() {
    let base = spawn_pty(RflexSim::new(RflexSimConfig::default()), no_waker()).unwrap();
    let folder = tempfile::tempdir().unwrap();
    let missing = folder.path().join("no-such-pad");
    let child =
        common::spawn_quiet(&["rflex", "teleop", "--port", &base.port_name, "--gamepad", missing.to_str().unwrap()]);
    let (code, stderr) = common::ended(child, Duration::from_secs(10));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("cannot open the gamepad"), "{stderr}");
    let (reply, state) = crossbeam_channel::bounded(1);
    base.command(RflexSimCommand::Inspect(reply));
    let state = state.recv_timeout(Duration::from_secs(10)).unwrap();
    assert!(state.braked && state.target_speed_m_per_s == 0.0, "{state:?}");
}

/// Ctrl-C or kill while driving: stopped at once, braked, and the signal's status.
#[test]
fn a_signal_while_driving_stops_and_brakes_the_base() {
    for (signal, status) in [("-INT", 130), ("-TERM", 143)] {
        let mut rig = Rig::start();
        rig.drives("a drive", &forward());
        let pid = rig.teleop.as_ref().unwrap().id().to_string();
        assert!(Process::new("kill").args([signal, &pid]).status().unwrap().success());
        let took = rig.stopped("the stop on a signal");
        rig.until("the brake set", HUNG, |command, _| *command == Command::BrakeSet);
        let (code, stderr) = common::ended(rig.teleop.take().unwrap(), Duration::from_secs(10));
        assert_eq!(code, Some(status), "{stderr}");
        assert!(stderr.contains("the base stopped and its brake is set"), "{stderr}");
        eprintln!("{signal}: stopped after {took:?}");
    }
}

/// `--deadman BTN_TR`: the right shoulder drives, the left does nothing.
#[test]
fn another_dead_man_button_can_be_chosen() {
    let mut rig = Rig::with(&["--deadman", "BTN_TR"]);
    let start_up = rig.received.len();
    rig.frame(&forward());
    rig.drives("a drive with the right shoulder", &[RawEvent::key(BTN_TR, true), RawEvent::abs(ABS_Y, -32768)]);
    let after = &rig.received[start_up..];
    let motion = after.iter().filter(|command| matches!(command, Command::AxisSetDir { .. })).count();
    assert_eq!(motion, 1, "the left shoulder drove nothing: {after:?}");
    rig.stops("the stop on its release", &[RawEvent::key(BTN_TR, false)]);
}
