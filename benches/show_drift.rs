//! A show's drift over a minute: two emulated servo boards and an emulated
//! PLEN2 behind the emulated Bluetooth-like bridge (`sim --link bursty`), on
//! pseudo-terminals, each cued every 15 s from 0 to 60 s, played by
//! `servo-studio play` (silent: the show's 0 on the system's monotonic
//! clock, as with a sound the player waits for the sound's point). Each
//! board logs what it takes in on the same clock (`sim --log`); printed per
//! device: each start's distance from its cue (taken in − due), and the
//! drift — the last start's distance less the first's. The target: every
//! start within one board update of its cue (servo board 10 ms; PLEN2 one
//! 32.768 ms cycle, which it starts on), so no drift over the minute.
//!
//! `cargo bench --bench show_drift` (about 70 s).

#![allow(clippy::expect_used, clippy::unwrap_used, clippy::cast_precision_loss)]

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

use servo_studio::project::plen2::{Frame, Motion, Plen2Project, Pose};
use servo_studio::project::{
    self, Action, Command as MacroCommand, Family, Macro, Project, Run, Servo, ServoProject, Step,
};
use servo_studio::show::{Cue, Device, Place, Show, Start};

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");
/// When each device is cued, ms.
const CUES_MS: [u64; 5] = [0, 15_000, 30_000, 45_000, 60_000];

fn servo_board() -> Project {
    let action = Action { id: 1, caption: "swing".into(), steps: vec![Step::new(1, 30, 50)] };
    let macros =
        vec![Macro { id: 1, caption: "show".into(), commands: vec![MacroCommand::once(Run::Action { action_id: 1 })] }];
    Project::servo(ServoProject {
        servos: vec![Servo::new(1, "arm")],
        actions: vec![action],
        macros,
        ..ServoProject::default()
    })
}

fn plen2() -> Project {
    let motion = Motion {
        slot: 2,
        name: "wave".into(),
        frames: vec![Frame::new(320, Pose::default()); 3],
        loop_range: None,
        jump_slot: None,
    };
    let mut project = Project::empty(Family::Plen2);
    project.plen2 = Plen2Project { motions: vec![motion], ..Plen2Project::default() };
    project
}

/// An emulator, its port and its log.
fn sim(dir: &Path, name: &str, project: &Project, extra: &[&str]) -> (Child, String, PathBuf) {
    let state = dir.join(format!("{name}.json"));
    project::save(&state, project).expect("the emulator's state is written");
    let log = dir.join(format!("{name}.log"));
    let mut args = vec![
        "sim",
        "--protocol",
        project.family.tag(),
        "--state",
        state.to_str().unwrap_or_default(),
        "--log",
        log.to_str().unwrap_or_default(),
    ];
    args.extend_from_slice(extra);
    let mut child = Command::new(EXE)
        .args(&args)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("the emulator starts");
    let mut port = String::new();
    BufReader::new(child.stdout.take().expect("its output")).read_line(&mut port).expect("it prints its port");
    (child, port.trim().to_string(), log)
}

/// The times (ns) a log's lines containing `wanted` were taken in.
fn taken_in(log: &Path, wanted: &str) -> Vec<i128> {
    let text = std::fs::read_to_string(log).unwrap_or_default();
    text.lines().filter(|line| line.contains(wanted)).filter_map(|line| line.split_once(' ')?.0.parse().ok()).collect()
}

fn main() {
    let dir = tempfile::tempdir().expect("a folder");
    let devices = [
        ("a", servo_board(), "ExecuteMacroRequest"),
        ("b", servo_board(), "ExecuteMacroRequest"),
        ("plen", plen2(), "$PM02"),
    ];
    let mut sims = Vec::new();
    for (name, project, _) in &devices {
        let extra: &[&str] = if *name == "plen" { &["--link", "bursty"] } else { &[] };
        sims.push(sim(dir.path(), name, project, extra));
    }
    let show = Show {
        devices: devices
            .iter()
            .map(|(name, project, _)| Device {
                name: (*name).into(),
                port: None,
                place: Place::default(),
                project: project.clone(),
                play_on_without: false,
            })
            .collect(),
        sound: None,
        cues: devices
            .iter()
            .flat_map(|(name, project, _)| {
                let start = if project.family == Family::Plen2 { Start::Slot(2) } else { Start::Macro(1) };
                CUES_MS.map(|at_ms| Cue { device: (*name).into(), at_ms, start })
            })
            .collect(),
    };
    let file = dir.path().join("show.json");
    std::fs::write(&file, show.to_json()).expect("the show is written");
    let mut args = vec!["play".to_string(), file.to_string_lossy().into_owned()];
    for ((name, ..), (_, port, _)) in devices.iter().zip(&sims) {
        args.extend(["--device".to_string(), format!("{name}={port}")]);
    }
    println!("a show of a minute: servo boards a and b, a PLEN2 behind a bursty bridge, each cued at {CUES_MS:?} ms");
    let output = Command::new(EXE).args(&args).stdin(Stdio::null()).output().expect("play runs");
    let said = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "play failed: {}", String::from_utf8_lossy(&output.stderr));
    let zero: i128 = said
        .lines()
        .find_map(|line| line.split_once("show's 0 at ")?.1.split_once(' ')?.0.parse().ok())
        .expect("the run's 0 is logged");
    for ((name, project, wanted), (mut child, _, log)) in devices.iter().zip(sims) {
        let update_ms = if project.family == Family::Plen2 { 32.768 } else { 10.0 };
        let starts = taken_in(&log, wanted);
        let offsets: Vec<f64> = starts
            .iter()
            .zip(CUES_MS)
            .map(|(&ns, at_ms)| (ns - zero - i128::from(at_ms) * 1_000_000) as f64 / 1e6)
            .collect();
        let worst = offsets.iter().fold(0.0_f64, |worst, offset| worst.max(offset.abs()));
        let drift = offsets.last().copied().unwrap_or(0.0) - offsets.first().copied().unwrap_or(0.0);
        let listed: Vec<String> = offsets.iter().map(|offset| format!("{offset:+.2}")).collect();
        println!(
            "  {name}: {} starts; taken in − due, ms: {}; drift over the minute {drift:+.2} ms; largest {worst:.2} ms (one update: {update_ms} ms{})",
            starts.len(),
            listed.join(", "),
            if project.family == Family::Plen2 {
                ", budgeted half a cycle early: it starts on its next cycle"
            } else {
                ""
            }
        );
        let _ = child.kill();
        let _ = child.wait();
    }
}
