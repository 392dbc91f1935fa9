//! `servo-studio play SHOW.json`: two servo boards and a PLEN2 behind a
//! bursty Bluetooth-like bridge (three emulators, each with `--log`), and an
//! rFLEX base. What is held here works on any machine however loaded: every
//! device answers and is started, no start is written before it is due, the
//! boards take their starts in at the cues' spacing (within half of it), a
//! signal stops every device (the base brakes) with the shell's status, and a
//! lost link stops the others. How close the starts are is a figure of the
//! machine: the command prints each start's skew, docs/show.md gives them.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss)]

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command as Process, Stdio};
use std::time::{Duration, Instant};

use servo_studio::project::plen2::{Frame, Motion, Plen2Project, Pose};
use servo_studio::project::{self, Action, Command, Family, Macro, Project, Run, Servo, ServoProject, Step};
use servo_studio::show::{Cue, Device, Place, Show, Start};

use crate::common;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

/// Servo 1 swinging `swings` times, 0.5 s each, macro 1 running them.
pub fn swinging(swings: i32) -> Project {
    let actions: Vec<Action> = (1..=swings)
        .map(|id| Action {
            id,
            caption: format!("swing {id}"),
            steps: vec![Step::new(1, if id % 2 == 0 { 30 } else { -30 }, 50)],
        })
        .collect();
    let commands = actions.iter().map(|a| Command::once(Run::Action { action_id: a.id })).collect();
    let macros = vec![Macro { id: 1, caption: "show".into(), commands }];
    Project::servo(ServoProject { servos: vec![Servo::new(1, "arm")], actions, macros, ..ServoProject::default() })
}

/// A PLEN2 holding a five-frame wave in slot 2.
pub fn waving() -> Project {
    let motion = Motion {
        slot: 2,
        name: "wave".into(),
        frames: vec![Frame::new(320, Pose::default()); 5],
        loop_range: None,
        jump_slot: None,
    };
    let mut project = Project::empty(Family::Plen2);
    project.plen2 = Plen2Project { motions: vec![motion], ..Plen2Project::default() };
    project
}

pub fn device(name: &str, project: Project) -> Device {
    Device { name: name.into(), port: None, place: Place::default(), project, play_on_without: false }
}

/// The log's lines (ns, command) once one contains `wanted`, waiting on the file itself.
pub fn logged_until(path: &Path, wanted: &str, within: Duration) -> Vec<(u128, String)> {
    logged_more(path, wanted, 0, within)
}

/// The log's lines once more than `seen` contain `wanted`.
fn logged_more(path: &Path, wanted: &str, seen: usize, within: Duration) -> Vec<(u128, String)> {
    let deadline = Instant::now() + within;
    loop {
        let text = std::fs::read_to_string(path).unwrap_or_default();
        let lines: Vec<(u128, String)> = text
            .lines()
            .filter_map(|line| {
                let (ns, said) = line.split_once(' ')?;
                Some((ns.parse().ok()?, said.to_string()))
            })
            .collect();
        if lines.iter().filter(|(_, said)| said.contains(wanted)).count() > seen {
            return lines;
        }
        assert!(Instant::now() < deadline, "{} never logged {wanted:?}: {text}", path.display());
        std::thread::yield_now();
    }
}

pub fn first(lines: &[(u128, String)], wanted: &str) -> u128 {
    lines.iter().find(|(_, said)| said.contains(wanted)).map(|(ns, _)| *ns).unwrap()
}

pub struct Stage {
    pub dir: tempfile::TempDir,
    pub sims: Vec<(String, common::Sim, PathBuf)>,
}

impl Stage {
    /// An emulator per device, preloaded with its project, logging.
    pub fn new(show: &Show, extra: &[(&str, &[&str])]) -> Self {
        let dir = tempfile::tempdir().unwrap();
        let mut sims = Vec::new();
        for device in &show.devices {
            let state = dir.path().join(format!("{}.json", device.name));
            project::save(&state, &device.project).unwrap();
            let log = dir.path().join(format!("{}.log", device.name));
            let family = device.project.family.tag();
            let mut args = vec!["--protocol", family, "--log", log.to_str().unwrap()];
            if device.project.family != Family::Rflex {
                args.extend(["--state", state.to_str().unwrap()]);
            }
            if let Some((_, more)) = extra.iter().find(|(name, _)| *name == device.name) {
                args.extend_from_slice(more);
            }
            sims.push((device.name.clone(), common::sim(&args), log));
        }
        std::fs::write(dir.path().join("show.json"), show.to_json()).unwrap();
        Self { dir, sims }
    }

    /// `--device NAME=PORT` for every emulator.
    pub fn device_args(&self) -> Vec<String> {
        self.sims.iter().flat_map(|(name, sim, _)| ["--device".to_string(), format!("{name}={}", sim.port)]).collect()
    }

    pub fn play(&self, more: &[&str]) -> Child {
        let mut args = vec!["play".to_string(), self.dir.path().join("show.json").to_str().unwrap().to_string()];
        args.extend(self.device_args());
        args.extend(more.iter().map(ToString::to_string));
        Process::new(EXE)
            .args(&args)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    }

    pub fn log(&self, name: &str) -> &Path {
        &self.sims.iter().find(|(n, ..)| n == name).unwrap().2
    }
}

#[test]
fn three_boards_start_on_their_cues_and_the_show_logs_each_start_and_its_skew() {
    let show = Show {
        devices: vec![device("a", swinging(4)), device("b", swinging(2)), device("plen", waving())],
        sound: None,
        cues: vec![
            Cue { device: "a".into(), at_ms: 0, start: Start::Macro(1) },
            Cue { device: "plen".into(), at_ms: 0, start: Start::Slot(2) },
            Cue { device: "b".into(), at_ms: 600, start: Start::Macro(1) },
        ],
    };
    let stage = Stage::new(&show, &[("plen", &["--link", "bursty"])]);
    let mut child = stage.play(&[]);
    let stdout = BufReader::new(child.stdout.take().unwrap()).lines().map(Result::unwrap).collect::<Vec<_>>();
    let (code, stderr) = common::ended(child, Duration::from_secs(60));
    assert_eq!(code, Some(0), "{stderr}");
    for name in ["a (Servo board) answered", "b (Servo board) answered", "plen (PLEN2) answered"] {
        assert!(stderr.contains(name), "{stderr}");
    }
    let said = stdout.join("\n");
    assert!(said.contains("run 1: ended after") && said.contains("largest skew"), "{said}");
    // Each start was written when due, never before (the log prints how late).
    let starts: Vec<&String> = stdout.iter().filter(|line| line.contains(" due at ")).collect();
    assert_eq!(starts.len(), 3, "{said}");
    assert!(starts.iter().all(|line| !line.contains(" -")), "{said}");
    // The boards took them in at the cues' spacing, on the system clock both sides read.
    let a = first(&logged_until(stage.log("a"), "ExecuteMacroRequest", Duration::from_secs(10)), "ExecuteMacroRequest");
    let b = first(&logged_until(stage.log("b"), "ExecuteMacroRequest", Duration::from_secs(10)), "ExecuteMacroRequest");
    let plen = first(&logged_until(stage.log("plen"), "$PM02", Duration::from_secs(10)), "$PM02");
    let gap_ms = (b - a) as f64 / 1e6;
    assert!((gap_ms - 600.0).abs() < 300.0, "b started {gap_ms:.1} ms after a; the cues are 600 ms apart");
    let together_ms = (plen as f64 - a as f64).abs() / 1e6;
    assert!(together_ms < 300.0, "a and the PLEN2 are cued together; {together_ms:.1} ms apart");
    eprintln!(
        "figures: b − a = {gap_ms:.2} ms (cued 600); |PLEN2 − a| = {together_ms:.2} ms (cued 0, the PLEN2 behind a bursty bridge)"
    );
}

#[test]
fn a_signal_stops_every_device_the_base_brakes_and_the_shell_gets_its_status() {
    let show = Show {
        devices: vec![
            device("arm", swinging(200)),
            device("plen", waving()),
            device("base", Project::empty(Family::Rflex)),
        ],
        sound: None,
        cues: vec![
            Cue { device: "arm".into(), at_ms: 0, start: Start::Macro(1) },
            Cue { device: "plen".into(), at_ms: 0, start: Start::Slot(2) },
            Cue {
                device: "base".into(),
                at_ms: 0,
                start: Start::Drive { speed_m_s: 0.2, turn_deg_s: 0.0, for_ms: 60_000 },
            },
        ],
    };
    let stage = Stage::new(&show, &[]);
    let count = |name: &str, wanted: &str| {
        std::fs::read_to_string(stage.log(name)).unwrap_or_default().lines().filter(|l| l.contains(wanted)).count()
    };
    for (signal, status) in [("-TERM", 143), ("-INT", 130)] {
        let (starts, drives) = (count("arm", "ExecuteMacroRequest"), count("base", "AxisSetDir"));
        let child = stage.play(&[]);
        logged_more(stage.log("arm"), "ExecuteMacroRequest", starts, Duration::from_secs(30));
        let before = logged_more(stage.log("base"), "AxisSetDir", drives, Duration::from_secs(30)).len();
        Process::new("kill").args([signal, &child.id().to_string()]).status().unwrap();
        let (code, stderr) = common::ended(child, Duration::from_secs(30));
        assert_eq!(code, Some(status), "{signal}: {stderr}");
        assert!(stderr.contains("every device was stopped"), "{stderr}");
        let arm = logged_until(stage.log("arm"), "SetServoParameterRequest", Duration::from_secs(10));
        assert!(arm.iter().any(|(_, said)| said.contains("is_start: false")), "the arm's servos stopped: {arm:?}");
        logged_until(stage.log("plen"), "#RI", Duration::from_secs(10));
        let base = logged_until(stage.log("base"), "BrakeSet", Duration::from_secs(10));
        assert!(
            base.iter().skip(before).any(|(_, said)| said.contains("BrakeSet")),
            "the base was told to brake after the signal: {base:?}"
        );
    }
}

#[test]
fn a_lost_link_stops_the_other_devices_and_says_which() {
    let show = Show {
        devices: vec![device("arm", swinging(200)), device("other", swinging(200))],
        sound: None,
        cues: vec![
            Cue { device: "arm".into(), at_ms: 0, start: Start::Macro(1) },
            Cue { device: "other".into(), at_ms: 0, start: Start::Macro(1) },
        ],
    };
    let mut stage = Stage::new(&show, &[]);
    let child = stage.play(&[]);
    logged_until(stage.log("other"), "ExecuteMacroRequest", Duration::from_secs(30));
    // The cable to "other" is pulled: its emulator goes.
    let (_, mut gone, _) = stage.sims.remove(1);
    gone.child.kill().unwrap();
    gone.child.wait().unwrap();
    let (code, stderr) = common::ended(child, Duration::from_secs(30));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("the link to other was lost") && stderr.contains("every device was stopped"), "{stderr}");
    let arm = logged_until(stage.log("arm"), "SetServoParameterRequest", Duration::from_secs(10));
    assert!(arm.iter().any(|(_, said)| said.contains("is_start: false")), "{arm:?}");
}

#[test]
fn a_project_file_plays_as_a_show_of_one_device() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("skull.json");
    project::save(&file, &swinging(2)).unwrap();
    let log = dir.path().join("skull.log");
    let sim = common::sim(&["--state", file.to_str().unwrap(), "--log", log.to_str().unwrap()]);
    let output = Process::new(EXE)
        .args(["play", file.to_str().unwrap(), "--device", &format!("skull={}", sim.port), "--loop", "2"])
        .output()
        .unwrap();
    let (said, stderr) = (String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("skull has no cue: playing macro 1 from the start"), "{stderr}");
    assert!(said.contains("run 2: ended after"), "{said}");
    let starts = logged_until(&log, "ExecuteMacroRequest", Duration::from_secs(10));
    assert_eq!(starts.iter().filter(|(_, s)| s.contains("ExecuteMacroRequest")).count(), 2, "two runs: {starts:?}");
}

#[test]
fn a_visitor_starts_each_run_with_a_gamepad_button() {
    use servo_studio::gamepad::{BTN_SOUTH, RawEvent};
    use std::io::Write as _;
    let show = Show {
        devices: vec![device("skull", swinging(1))],
        sound: None,
        cues: vec![Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(1) }],
    };
    let stage = Stage::new(&show, &[]);
    let fifo = stage.dir.path().join("pad");
    assert!(Process::new("mkfifo").arg(&fifo).status().unwrap().success());
    let mut child = stage.play(&["--wait-gamepad", &format!("{}:BTN_SOUTH", fifo.display()), "--loop", "2"]);
    // Opening for writing waits for the player to open it for reading.
    let mut pad = std::fs::OpenOptions::new().write(true).open(&fifo).unwrap();
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut waits_for = |run: u32| loop {
        let mut line = String::new();
        assert!(stderr.read_line(&mut line).unwrap() > 0, "the player ended before run {run} waited");
        if line.contains(&format!("run {run} waits for BTN_SOUTH")) {
            return;
        }
    };
    let press = |pad: &mut std::fs::File, down: bool| {
        let mut bytes = RawEvent::key(BTN_SOUTH, down).to_bytes(0).to_vec();
        bytes.extend(RawEvent::report().to_bytes(0));
        pad.write_all(&bytes).unwrap();
    };
    for run in 1..=2 {
        waits_for(run);
        let started =
            std::fs::read_to_string(stage.log("skull")).unwrap_or_default().matches("ExecuteMacroRequest").count();
        assert_eq!(started, usize::try_from(run - 1).unwrap(), "run {run} has not started before the press");
        press(&mut pad, true);
        logged_more(stage.log("skull"), "ExecuteMacroRequest", started, Duration::from_secs(30));
        press(&mut pad, false);
    }
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(0));
}

#[test]
fn a_device_marked_play_on_without_it_is_left_behind_and_the_show_goes_on() {
    let mut other = device("other", swinging(6));
    other.play_on_without = true;
    let show = Show {
        devices: vec![device("arm", swinging(6)), other],
        sound: None,
        cues: vec![
            Cue { device: "arm".into(), at_ms: 0, start: Start::Macro(1) },
            Cue { device: "other".into(), at_ms: 0, start: Start::Macro(1) },
        ],
    };
    let mut stage = Stage::new(&show, &[]);
    let mut child = stage.play(&[]);
    logged_until(stage.log("other"), "ExecuteMacroRequest", Duration::from_secs(30));
    let (_, mut gone, _) = stage.sims.remove(1);
    gone.child.kill().unwrap();
    gone.child.wait().unwrap();
    let stdout =
        BufReader::new(child.stdout.take().unwrap()).lines().map(Result::unwrap).collect::<Vec<_>>().join("\n");
    let (code, stderr) = common::ended(child, Duration::from_secs(60));
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stdout.contains("the link to other was lost") && stdout.contains("played on without it"), "{stdout}");
    let arm = std::fs::read_to_string(stage.log("arm")).unwrap();
    assert!(!arm.contains("is_start: false"), "the arm was not stopped: {arm}");
}

/// A device named by the USB id of its adapter is looked for among the USB
/// serial devices attached; one that is not attached ends the run before
/// anything moves, naming the id and what is attached.
#[test]
fn a_device_found_by_usb_id_that_is_not_attached_is_said_before_anything_moves() {
    let stage = Stage::new(&two_boards_for_ids(), &[]);
    let skull = stage.device_args()[1].clone();
    let show = stage.dir.path().join("show.json");
    let output = Process::new(EXE)
        .args(["play", show.to_str().unwrap(), "--device", &skull, "--device", "arms=usb:0403:6001:NOT-HERE"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("arms (Servo board) did not answer on usb:0403:6001:NOT-HERE"), "{stderr}");
    assert!(stderr.contains("no USB serial device usb:0403:6001:NOT-HERE is attached"), "{stderr}");
    let started = std::fs::read_to_string(stage.log("skull")).unwrap_or_default();
    assert!(!started.contains("ExecuteMacroRequest"), "nothing moved: {started}");
    let malformed = Process::new(EXE)
        .args(["play", show.to_str().unwrap(), "--device", &skull, "--device", "arms=usb:ftdi"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&malformed.stderr);
    assert!(stderr.contains("\"usb:ftdi\" is not a USB id: write usb:VID:PID"), "{stderr}");
}

fn two_boards_for_ids() -> Show {
    Show {
        devices: vec![device("skull", swinging(2)), device("arms", swinging(2))],
        sound: None,
        cues: vec![Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(1) }],
    }
}
