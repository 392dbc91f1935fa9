//! `servo-studio play` over bad links, every family: a port that accepts and
//! never answers, a device that goes silent mid-show (its link still open), a
//! bridge that holds every byte 40 ms each way, and a cable pulled and put
//! back between runs. The emulators sit behind a proxy (`common::proxy`) and
//! log what they take in. Verdicts are on what the player decided — who it
//! named, what it stopped, how far ahead it sent a start — never on how fast
//! the machine is; the timing the boards saw is printed as figures.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss)]

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command as Process, Stdio};
use std::time::{Duration, Instant};

use servo_studio::project::{self, Family, Project};
use servo_studio::show::{Cue, Device, Place, Show, Start};

use super::play::{first, logged_until, swinging, waving};
use crate::common::{self, proxy::Proxy, proxy::Silent};

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");
const LONG: Duration = Duration::from_secs(30);

/// An emulated board on TCP, logging, maybe behind a proxy.
struct Board {
    name: String,
    _sim: common::Sim,
    log: PathBuf,
    proxy: Option<Proxy>,
    port: String,
}

fn board(dir: &Path, name: &str, project: &Project, delay: Option<Duration>) -> Board {
    let state = dir.join(format!("{name}.json"));
    project::save(&state, project).unwrap();
    let log = dir.join(format!("{name}.log"));
    let family = project.family.tag();
    let mut args = vec!["--protocol", family, "--log", log.to_str().unwrap(), "--tcp", "127.0.0.1:0"];
    if project.family != Family::Rflex {
        args.extend(["--state", state.to_str().unwrap()]);
    }
    let sim = common::sim(&args);
    let proxy = delay.map(|delay| Proxy::new(&sim.port, delay));
    let port = proxy.as_ref().map_or_else(|| sim.port.clone(), |proxy| proxy.port.clone());
    Board { name: name.into(), _sim: sim, log, proxy, port }
}

fn device(name: &str, project: Project, play_on_without: bool) -> Device {
    Device { name: name.into(), port: None, place: Place::default(), project, play_on_without }
}

/// `play` on `show` with each device at its port (`ports`: name, port).
fn play(dir: &Path, show: &Show, ports: &[(&str, &str)], more: &[&str]) -> Child {
    let file = dir.join("show.json");
    std::fs::write(&file, show.to_json()).unwrap();
    let mut args = vec!["play".to_string(), file.to_str().unwrap().to_string()];
    for (name, port) in ports {
        args.extend(["--device".to_string(), format!("{name}={port}")]);
    }
    args.extend(more.iter().map(ToString::to_string));
    Process::new(EXE).args(&args).stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap()
}

fn count(log: &Path, wanted: &str) -> usize {
    std::fs::read_to_string(log).unwrap_or_default().matches(wanted).count()
}

/// A long-running cue for a device of `family`, and what its board logs when it starts.
fn long_cue(family: Family) -> (Start, &'static str) {
    match family {
        family if family == Family::Servo => (Start::Macro(1), "ExecuteMacroRequest"),
        family if family == Family::Plen2 => (Start::Slot(2), "$PM02"),
        _ => (Start::Drive { speed_m_s: 0.1, turn_deg_s: 0.0, for_ms: 60_000 }, "AxisSetDir { axis: 0, speed: 1"),
    }
}

fn project_of(family: Family) -> Project {
    match family {
        family if family == Family::Servo => swinging(200),
        family if family == Family::Plen2 => waving(),
        _ => Project::empty(Family::Rflex),
    }
}

#[test]
fn a_device_whose_port_accepts_and_never_answers_is_named_and_nothing_plays() {
    for family in [Family::Servo, Family::Plen2, Family::Rflex] {
        let dir = tempfile::tempdir().unwrap();
        let arm = board(dir.path(), "arm", &swinging(4), None);
        let silent = Silent::new();
        let (start, _) = long_cue(family);
        let show = Show {
            devices: vec![device("arm", swinging(4), false), device("mute", project_of(family), false)],
            sound: None,
            cues: vec![
                Cue { device: "arm".into(), at_ms: 0, start: Start::Macro(1) },
                Cue { device: "mute".into(), at_ms: 0, start },
            ],
        };
        let child = play(dir.path(), &show, &[("arm", &arm.port), ("mute", &silent.port)], &[]);
        let (code, stderr) = common::ended(child, LONG);
        assert_eq!(code, Some(1), "{family:?}: {stderr}");
        let named = format!("mute ({}) did not answer on {}", family.name(), silent.port);
        assert!(stderr.contains(&named), "{family:?}: {stderr}");
        assert_eq!(count(&arm.log, "ExecuteMacroRequest"), 0, "{family:?}: nothing played");
        assert!(silent.received.load(std::sync::atomic::Ordering::SeqCst) > 0, "it was asked");
    }
}

#[test]
fn a_device_that_goes_silent_mid_show_stops_every_device_and_is_named() {
    for family in [Family::Servo, Family::Plen2, Family::Rflex] {
        let dir = tempfile::tempdir().unwrap();
        let arm = board(dir.path(), "arm", &swinging(200), None);
        let mute = board(dir.path(), "mute", &project_of(family), Some(Duration::ZERO));
        let (start, started) = long_cue(family);
        let show = Show {
            devices: vec![device("arm", swinging(200), false), device("mute", project_of(family), false)],
            sound: None,
            cues: vec![
                Cue { device: "arm".into(), at_ms: 0, start: Start::Macro(1) },
                Cue { device: "mute".into(), at_ms: 0, start },
            ],
        };
        let child = play(dir.path(), &show, &[("arm", &arm.port), ("mute", &mute.port)], &[]);
        logged_until(&mute.log, started, LONG);
        logged_until(&arm.log, "ExecuteMacroRequest", LONG);
        // It still hears; it never answers again. Its link stays open.
        let silenced = Instant::now();
        mute.proxy.as_ref().unwrap().silence(true);
        let (code, stderr) = common::ended(child, LONG);
        eprintln!("figure: {family:?} gone silent: the show stopped {:.1} s later", silenced.elapsed().as_secs_f64());
        assert_eq!(code, Some(1), "{family:?}: {stderr}");
        assert!(
            stderr.contains("the link to mute was lost (it stopped answering")
                && stderr.contains("every device was stopped"),
            "{family:?}: {stderr}"
        );
        let stopped = logged_until(&arm.log, "is_start: false", LONG);
        assert!(!stopped.is_empty(), "{family:?}: the arm was stopped");
        // The silent device was told to stop too (its board heard it).
        let stop = match family {
            family if family == Family::Servo => "is_start: false",
            family if family == Family::Plen2 => "#RI",
            _ => "BrakeSet",
        };
        logged_until(&mute.log, stop, LONG);
    }
}

#[test]
fn a_device_marked_play_on_without_it_that_goes_silent_is_left_behind() {
    let dir = tempfile::tempdir().unwrap();
    let arm = board(dir.path(), "arm", &swinging(12), None);
    let base = board(dir.path(), "base", &Project::empty(Family::Rflex), Some(Duration::ZERO));
    let (_, started) = long_cue(Family::Rflex);
    let show = Show {
        devices: vec![device("arm", swinging(12), false), device("base", Project::empty(Family::Rflex), true)],
        sound: None,
        cues: vec![
            Cue { device: "arm".into(), at_ms: 0, start: Start::Macro(1) },
            Cue {
                device: "base".into(),
                at_ms: 0,
                start: Start::Drive { speed_m_s: 0.1, turn_deg_s: 0.0, for_ms: 3_000 },
            },
        ],
    };
    let mut child = play(dir.path(), &show, &[("arm", &arm.port), ("base", &base.port)], &[]);
    logged_until(&base.log, started, LONG);
    base.proxy.as_ref().unwrap().silence(true);
    let stdout = BufReader::new(child.stdout.take().unwrap()).lines().map(Result::unwrap).collect::<Vec<_>>();
    let (code, stderr) = common::ended(child, LONG);
    assert_eq!(code, Some(0), "{stderr}");
    let said = stdout.join("\n");
    assert!(
        said.contains("the link to base was lost (it stopped answering") && said.contains("played on without it"),
        "{said}"
    );
    assert_eq!(count(&arm.log, "is_start: false"), 0, "the arm played on");
    // It could not answer, but it still heard: it was told to stop and brake, never left driving.
    logged_until(&base.log, "BrakeSet", LONG);
}

/// What `play` said of a device when it answered: its start delay and its link's one-way delay, ms.
fn answered(stderr: &str, name: &str) -> (f64, f64) {
    let line = stderr.lines().find(|line| line.starts_with(&format!("{name} ("))).unwrap_or_else(|| panic!("{stderr}"));
    let number_after = |text: &str| -> f64 {
        line.split(text).nth(1).and_then(|rest| rest.split_whitespace().next()).unwrap().parse().unwrap()
    };
    (number_after("its start takes "), number_after("its link "))
}

/// When `play` wrote each device's start due, ns (its log's "due at").
fn due_ns(stdout: &[String], name: &str) -> u128 {
    let line = stdout.iter().find(|line| line.contains(&format!(": {name} ")) && line.contains(" due at ")).unwrap();
    line.split(" due at ").nth(1).unwrap().split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn every_familys_link_delay_is_measured_and_its_start_sent_that_much_earlier() {
    let bridge = Duration::from_millis(40);
    let dir = tempfile::tempdir().unwrap();
    let arm = board(dir.path(), "arm", &swinging(2), None);
    let skull = board(dir.path(), "skull", &swinging(2), Some(bridge));
    let plen = board(dir.path(), "plen", &waving(), Some(bridge));
    let base = board(dir.path(), "base", &Project::empty(Family::Rflex), Some(bridge));
    let drive = Start::Drive { speed_m_s: 0.1, turn_deg_s: 0.0, for_ms: 500 };
    let show = Show {
        devices: vec![
            device("arm", swinging(2), false),
            device("skull", swinging(2), false),
            device("plen", waving(), false),
            device("base", Project::empty(Family::Rflex), false),
        ],
        sound: None,
        cues: ["arm", "skull", "plen"]
            .iter()
            .zip([Start::Macro(1), Start::Macro(1), Start::Slot(2)])
            .map(|(name, start)| Cue { device: (*name).into(), at_ms: 0, start })
            .chain([Cue { device: "base".into(), at_ms: 0, start: drive }])
            .collect(),
    };
    let ports: Vec<(&str, &str)> =
        [&arm, &skull, &plen, &base].iter().map(|board| (board.name.as_str(), board.port.as_str())).collect();
    let mut child = play(dir.path(), &show, &ports, &[]);
    let stdout = BufReader::new(child.stdout.take().unwrap()).lines().map(Result::unwrap).collect::<Vec<_>>();
    let (code, stderr) = common::ended(child, Duration::from_secs(60));
    assert_eq!(code, Some(0), "{stderr}");
    // Measured from real round trips: at least the bridge's 40 ms one way, for every family behind it.
    let (_, arm_link) = answered(&stderr, "arm");
    assert!(arm_link < 40.0, "{stderr}");
    for name in ["skull", "plen", "base"] {
        let (start_ms, link_ms) = answered(&stderr, name);
        assert!(link_ms >= 40.0 && start_ms >= link_ms, "{name}: {stderr}");
        // Each start written that much earlier than the direct board's, for the same cue.
        let ahead_ms = (due_ns(&stdout, "arm") as f64 - due_ns(&stdout, name) as f64) / 1e6;
        assert!(ahead_ms >= 40.0 - arm_link, "{name} written {ahead_ms:.1} ms ahead of the arm: {stdout:?}");
    }
    let said = stdout.join("\n");
    assert!(said.contains("± ") && said.contains("half its cycle") && said.contains("largest skew"), "{said}");
    // The figures: when each board took its start in, against the direct one.
    let taken = |board: &Board, wanted: &str| first(&logged_until(&board.log, wanted, LONG), wanted) as f64;
    let arm_ns = taken(&arm, "ExecuteMacroRequest");
    let skull_ms = (taken(&skull, "ExecuteMacroRequest") - arm_ns) / 1e6;
    // A PLEN2 is sent half a cycle early (it starts at its next cycle, 0–32.8 ms after it reads the command).
    let plen_ms = (taken(&plen, "$PM02") - arm_ns) / 1e6 + 16.384;
    let base_ms = (taken(&base, "AxisSetDir { axis: 0, speed: 1") - arm_ns) / 1e6;
    eprintln!(
        "figures behind a 40 ms bridge, against a board on a direct link: servo board {skull_ms:+.1} ms, PLEN2 {plen_ms:+.1} ms (± 16.4 ms its cycle), base {base_ms:+.1} ms"
    );
    for (name, off_ms) in [("skull", skull_ms), ("plen", plen_ms), ("base", base_ms)] {
        assert!(off_ms.abs() < 300.0, "{name} {off_ms:.1} ms off");
    }
}

#[test]
fn a_device_lost_in_one_run_is_connected_again_for_the_next_once_its_link_is_back() {
    let dir = tempfile::tempdir().unwrap();
    let arm = board(dir.path(), "arm", &swinging(4), None);
    let plen = board(dir.path(), "plen", &waving(), Some(Duration::ZERO));
    let show = Show {
        devices: vec![device("arm", swinging(4), false), device("plen", waving(), true)],
        sound: None,
        cues: vec![
            Cue { device: "arm".into(), at_ms: 0, start: Start::Macro(1) },
            Cue { device: "plen".into(), at_ms: 0, start: Start::Slot(2) },
        ],
    };
    let mut child = play(dir.path(), &show, &[("arm", &arm.port), ("plen", &plen.port)], &["--loop", "3"]);
    let stdout = BufReader::new(child.stdout.take().unwrap());
    logged_until(&plen.log, "$PM02", LONG);
    let proxy = plen.proxy.as_ref().unwrap();
    proxy.cut();
    let mut lines = stdout.lines().map(Result::unwrap);
    let lost = lines.by_ref().find(|line| line.contains("the link to plen was lost"));
    assert!(lost.is_some(), "run 1 went on without it");
    proxy.restore();
    let rest: Vec<String> = lines.collect();
    let (code, stderr) = common::ended(child, Duration::from_secs(60));
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(stderr.matches("plen (PLEN2) answered on").count(), 2, "connected again: {stderr}");
    assert!(count(&plen.log, "$PM02") >= 2, "it played again after the cable was back: {rest:?}");
    assert_eq!(count(&arm.log, "ExecuteMacroRequest"), 3, "every run played the arm");
}

#[test]
fn a_device_that_went_silent_is_connected_again_once_it_answers() {
    let dir = tempfile::tempdir().unwrap();
    let arm = board(dir.path(), "arm", &swinging(12), None);
    let base = board(dir.path(), "base", &Project::empty(Family::Rflex), Some(Duration::ZERO));
    let show = Show {
        devices: vec![device("arm", swinging(12), false), device("base", Project::empty(Family::Rflex), true)],
        sound: None,
        cues: vec![
            Cue { device: "arm".into(), at_ms: 0, start: Start::Macro(1) },
            Cue {
                device: "base".into(),
                at_ms: 0,
                start: Start::Drive { speed_m_s: 0.1, turn_deg_s: 0.0, for_ms: 1_000 },
            },
        ],
    };
    let mut child = play(dir.path(), &show, &[("arm", &arm.port), ("base", &base.port)], &["--loop", "2"]);
    let stdout = BufReader::new(child.stdout.take().unwrap());
    logged_until(&base.log, "AxisSetDir { axis: 0, speed: 1", LONG);
    let proxy = base.proxy.as_ref().unwrap();
    proxy.silence(true);
    let mut lines = stdout.lines().map(Result::unwrap);
    assert!(lines.by_ref().any(|line| line.contains("the link to base was lost (it stopped answering")), "run 1");
    // It answers again: its old link is let go and run 2 connects it anew.
    proxy.silence(false);
    let rest: Vec<String> = lines.collect();
    let (code, stderr) = common::ended(child, Duration::from_secs(60));
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(stderr.matches("base (rFLEX base) answered on").count(), 2, "connected again: {stderr} {rest:?}");
    assert!(!rest.iter().any(|line| line.starts_with("run 2: the link to base was lost")), "{rest:?}");
}
