//! The DYNAMIXEL family in the editor, on its emulated bus: the scan, live
//! moves within limits, a hardware error said at once, posing by hand
//! (capture and record, each one undo step), a motion streamed as its plot
//! draws it and STOP holding the servos; and the files outside its folders
//! that name it.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

use super::*;
use crate::sim::dynamixel::{BusCommand, Fault as DynamixelFault};
use crate::ui::StudioApp;

fn editor(project: Project) -> Harness<'static, StudioApp> {
    crate::ui::test_editor(project, egui::vec2(1280.0, 800.0))
}

fn run_until(harness: &mut Harness<'static, StudioApp>, what: &str, done: impl Fn(&StudioApp) -> bool) {
    let deadline = Instant::now() + Duration::from_secs(30);
    while !done(harness.state()) {
        assert!(Instant::now() < deadline, "timed out waiting for {what}");
        harness.step();
        std::thread::yield_now();
    }
}

fn dynamixel(app: &StudioApp) -> &DynamixelUi {
    app.families.of().expect("the DYNAMIXEL family is in the editor")
}

fn at(app: &StudioApp, id: u8) -> Option<u32> {
    dynamixel(app).bus.servos.get(&id)?.reading.map(|reading| reading.position)
}

/// Does `command` to the demo bus.
fn on_bus(harness: &Harness<'static, StudioApp>, command: BusCommand) {
    let bus = harness.state().link.as_ref().and_then(BoardLink::emulated::<link::EmulatedBus>).expect("the demo bus");
    bus.command(command);
}

/// The editor on the demo bus, scanned: every servo found, read and its limits known.
fn on_the_demo_bus(project: Project) -> Harness<'static, StudioApp> {
    let mut harness = editor(project);
    harness.run_steps(2);
    assert_eq!(harness.state().window.tab, Tab::Bus, "the bus is where the editor opens");
    harness.get_by_label("Demo board").click();
    run_until(&mut harness, "the scan", |app| {
        let family = dynamixel(app);
        family.bus.scanning.is_none()
            && family.bus.servos.len() == 3
            && family.bus.servos.values().all(|servo| servo.limits.is_some() && servo.reading.is_some())
    });
    harness
}

#[test]
fn the_demo_bus_is_scanned_in_both_protocols_and_each_servo_moves_live_within_its_limits() {
    let mut harness = on_the_demo_bus(Project::empty(Family::Dynamixel));
    harness.run_steps(2);
    for listed in ["XL430-W250 v46 · 2.0", "XM430-W350 v46 · 2.0", "AX-12A v24 · 1.0"] {
        assert!(harness.query_by_label(listed).is_some(), "{listed} is listed");
    }
    assert_eq!(harness.state().status.as_ref().unwrap().text, "Scan done: 3 servos found");
    // The packet log holds the scan: the broadcast ping out, each servo's status back.
    let log = &mut harness.state_mut().link.as_mut().unwrap().log;
    let lines: Vec<String> = log.visible().iter().map(|entry| entry.line()).collect();
    assert!(
        lines.iter().any(|line| line.contains("→ PING ID all · 2.0 · 0 bytes [ff ff fd 00 fe 03 00 01 31 42]")),
        "{lines:?}"
    );
    assert!(lines.iter().any(|line| line.contains("← STATUS ID 1 · 2.0 · error 0x00 · 3 bytes")), "{lines:?}");
    assert!(lines.iter().any(|line| line.contains("→ PING ID 3 · 1.0")), "{lines:?}");
    harness.get_by_label("Torque on (all)").click();
    harness.step();
    harness.state_mut().apply(Action::family(DynamixelAction::Goal { id: 1, position: 3072 }));
    // Past the AX's 1023: clamped to its limit, never sent beyond it.
    harness.state_mut().apply(Action::family(DynamixelAction::Goal { id: 3, position: 5000 }));
    assert_eq!(dynamixel(harness.state()).bus.servos[&3].goal, Some(1023));
    run_until(&mut harness, "the goals reached", |app| at(app, 1) == Some(3072) && at(app, 3) == Some(1023));

    // STOP holds every servo where it is, and moves wait for Resume.
    harness.get_by_label("■ STOP").click();
    harness.step();
    assert_eq!(harness.state().status.as_ref().unwrap().text, "STOP: every servo holds where it is");
    harness.state_mut().apply(Action::family(DynamixelAction::Goal { id: 1, position: 1000 }));
    assert!(harness.state().status.as_ref().unwrap().text.contains("press Resume"));
}

#[test]
fn an_overheating_servo_is_said_at_once_and_shown_in_its_row() {
    let mut harness = on_the_demo_bus(Project::empty(Family::Dynamixel));
    on_bus(&harness, BusCommand::Fault { id: 2, fault: DynamixelFault::Overheating });
    run_until(&mut harness, "the overheating said", |app| {
        app.status.as_ref().is_some_and(|status| status.text.starts_with("Servo 2: overheating!"))
    });
    assert!(harness.state().status.as_ref().unwrap().is_error);
    harness.run_steps(2);
    assert!(harness.query_by_label("overheating").is_some(), "its row says it");
    assert!(harness.query_by_label("83 °C").is_some(), "past its 80 °C limit");
}

#[test]
fn a_pose_made_by_hand_is_captured_into_a_step_and_undone_in_one_step() {
    let mut harness = on_the_demo_bus(Project::empty(Family::Dynamixel));
    harness.state_mut().apply(Action::family(DynamixelAction::Torque { id: None, on: false }));
    on_bus(&harness, BusCommand::Hand { id: 1, position: 2600 });
    on_bus(&harness, BusCommand::Hand { id: 3, position: 300 });
    run_until(&mut harness, "the hand's pose read", |app| at(app, 1) == Some(2600) && at(app, 3) == Some(300));
    harness.get_by_label("Capture pose (C)").click();
    harness.run_steps(2);
    let section = DynamixelSection::of(&harness.state().document.project);
    assert_eq!(section.motions.len(), 1);
    assert_eq!(section.motions[0].steps[0].positions, [(1, 2600), (2, 2048), (3, 300)].into());
    let ids: Vec<(u8, u16)> = section.servos.iter().map(|servo| (servo.id, servo.model_number)).collect();
    assert_eq!(ids, [(1, 1060), (2, 1020), (3, 12)], "the bus's servos kept with their models");
    // The key C captures too: a second step.
    on_bus(&harness, BusCommand::Hand { id: 1, position: 2700 });
    run_until(&mut harness, "the second pose read", |app| at(app, 1) == Some(2700));
    harness.key_press(egui::Key::C);
    harness.run_steps(2);
    let section = DynamixelSection::of(&harness.state().document.project);
    assert_eq!(section.motions[0].steps.len(), 2);
    assert_eq!(section.motions[0].steps[1].positions[&1], 2700);
    harness.state_mut().apply(Action::Undo);
    assert_eq!(DynamixelSection::of(&harness.state().document.project).motions[0].steps.len(), 1, "one capture undone");
}

#[test]
fn a_performance_recorded_by_hand_is_fitted_into_steps_within_the_tolerance() {
    let mut harness = on_the_demo_bus(Project::empty(Family::Dynamixel));
    harness.state_mut().apply(Action::family(DynamixelAction::Torque { id: None, on: false }));
    harness.state_mut().apply(Action::family(DynamixelAction::Record(true)));
    // The hand sweeps servo 1 up 35° and back in strides under the tolerance
    // (10 units, 0.88°), each held for two readings, as a hand moves.
    let sweep: Vec<u32> = (0..=40).map(|k| 2048 + k * 10).chain((0..=40).rev().map(|k| 2048 + k * 10)).collect();
    let read_at = |app: &StudioApp| dynamixel(app).bus.servos[&1].reading.map(|reading| reading.at);
    for position in &sweep {
        on_bus(&harness, BusCommand::Hand { id: 1, position: *position });
        run_until(&mut harness, "the hand read", |app| at(app, 1) == Some(*position));
        let before = read_at(harness.state());
        run_until(&mut harness, "another reading", |app| read_at(app) != before);
    }
    harness.state_mut().apply(Action::family(DynamixelAction::Record(false)));
    let section = DynamixelSection::of(&harness.state().document.project);
    let motion = section.motions.last().expect("a motion from the recording");
    assert!(!motion.steps.is_empty());
    // Up and back: a few straight steps, not a step a stride.
    assert!(motion.steps.len() <= 6, "{} steps for a sweep up and back", motion.steps.len());
    let end = motion.steps.last().unwrap().positions[&1];
    assert!(end.abs_diff(2048) <= 12, "it ends where the hand left it (within 1°): {end}");
    let top = motion.steps.iter().map(|step| step.positions[&1]).max().unwrap();
    assert!(top.abs_diff(2448) <= 12, "it reaches the sweep's top (within 1°): {top}");
    assert!(harness.state().status.as_ref().unwrap().text.starts_with("Recorded "));
    harness.state_mut().apply(Action::Undo);
    assert!(DynamixelSection::of(&harness.state().document.project).motions.is_empty(), "one recording undone");
}

/// A recording whose cable is pulled mid-way is not lost: Stop recording,
/// with no bus any more, still fits what it took into a motion.
#[test]
fn a_recording_outlives_a_pulled_cable() {
    let mut harness = on_the_demo_bus(Project::empty(Family::Dynamixel));
    harness.state_mut().apply(Action::family(DynamixelAction::Torque { id: None, on: false }));
    harness.state_mut().apply(Action::family(DynamixelAction::Record(true)));
    for position in [2100, 2200, 2300] {
        on_bus(&harness, BusCommand::Hand { id: 1, position });
        run_until(&mut harness, "the hand read", |app| at(app, 1) == Some(position));
    }
    on_bus(&harness, BusCommand::Unplug);
    run_until(&mut harness, "the link lost", |app| app.link.is_none());
    harness.run_steps(2);
    harness.get_by_label("■ Stop recording").click();
    harness.run_steps(2);
    let section = DynamixelSection::of(&harness.state().document.project);
    let motion = section.motions.last().expect("the recording kept as a motion");
    let end = motion.steps.last().unwrap().positions[&1];
    assert!(end.abs_diff(2300) <= 12, "it ends where the hand last was: {end}");
}

#[test]
fn a_motion_is_streamed_to_the_servos_as_its_plot_draws_it_and_stop_holds_them() {
    let section = DynamixelSection {
        servos: vec![
            ServoSetup { id: 1, name: "肩 shoulder".into(), model_number: 1060, profile: None },
            ServoSetup { id: 3, name: "腕".into(), model_number: 12, profile: None },
        ],
        motions: vec![Motion {
            name: "揮手 wave".into(),
            steps: vec![
                Step { duration_ms: 400, easing: Easing::EaseInOut, positions: [(1, 2548), (3, 612)].into() },
                Step { duration_ms: 400, easing: Easing::Linear, positions: [(1, 2248), (3, 412)].into() },
            ],
        }],
    };
    let mut project = Project::empty(Family::Dynamixel);
    project.sections.set(Family::Dynamixel, section.kept());
    let mut harness = on_the_demo_bus(project);
    harness.state_mut().apply(Action::family(DynamixelAction::Torque { id: None, on: true }));
    harness.state_mut().apply(Action::family(DynamixelAction::Play(0)));
    assert!(dynamixel(harness.state()).playing.is_some());
    // The frames streamed are the motion's poses, every 20 ms, as the plot samples them.
    let from: std::collections::BTreeMap<u8, u32> = [(1, 2048), (2, 2048), (3, 512)].into();
    let frames = state::frames(&section.motions[0], &dynamixel(harness.state()).bus);
    assert_eq!(frames.len(), 40);
    for (k, frame) in frames.iter().enumerate() {
        let pose = section.motions[0].pose_at(&from, (k as f64 + 1.0) * 20.0);
        assert_eq!(frame, &pose.into_iter().collect::<Vec<_>>(), "frame {k}");
    }
    run_until(&mut harness, "the motion played", |app| {
        dynamixel(app).playing.is_none() && at(app, 1) == Some(2248) && at(app, 3) == Some(412)
    });

    // Played again and stopped at once: the servos hold short of its end.
    harness.state_mut().apply(Action::family(DynamixelAction::Play(0)));
    harness.get_by_label("■ STOP").click();
    harness.run_steps(2);
    assert!(dynamixel(harness.state()).playing.is_none());
    let held = at(harness.state(), 1);
    let deadline = Instant::now() + Duration::from_millis(600);
    while Instant::now() < deadline {
        harness.step();
        std::thread::yield_now();
    }
    assert_ne!(at(harness.state(), 1), Some(2548), "never reached the motion's first pose: {held:?}");
}

/// Files of `src/` outside the DYNAMIXEL family's folders whose code names
/// it (`Family::Dynamixel`, a `dynamixel::` path, a `Dynamixel…` type); a
/// layer's `mod dynamixel;` is the door to the family's folder in it, and
/// prose (a RoboPlus file's "Dynamixel id") names no code.
fn shared_files_naming_dynamixel() -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let own: Vec<PathBuf> = ["protocol", "device", "sim", "ui", "show/stages"]
        .iter()
        .map(|layer| root.join("src").join(layer).join("dynamixel"))
        .chain(
            ["src/cli/dynamixel.rs", "src/project/dynamixel.rs", "src/interchange/dynamixel.rs"]
                .map(|own| root.join(own)),
        )
        .collect();
    let mut found = Vec::new();
    let mut folders = vec![root.join("src")];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).unwrap() {
            let path: PathBuf = entry.unwrap().path();
            if own.contains(&path) {
                continue;
            }
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|ending| ending == "rs") {
                let text = std::fs::read_to_string(&path).unwrap();
                let names_code = |line: &str| {
                    line.contains("Family::Dynamixel")
                        || line.contains("dynamixel::")
                        || line
                            .match_indices("Dynamixel")
                            .any(|(at, _)| line[at + "Dynamixel".len()..].starts_with(|c: char| c.is_ascii_uppercase()))
                };
                let naming = text
                    .lines()
                    .filter(|line| !line.trim_start().starts_with("//"))
                    .any(|line| names_code(line) && !matches!(line.trim(), "mod dynamixel;" | "pub mod dynamixel;"));
                if naming {
                    found.push(path.strip_prefix(root).unwrap().display().to_string());
                }
            }
        }
    }
    found.sort();
    found
}

/// Built through the seam: besides each layer's `mod dynamixel;`, at most
/// four shared files name the family, and ARCHITECTURE.md names them.
#[test]
fn the_dynamixel_family_touches_only_the_shared_files_named() {
    let touched = shared_files_naming_dynamixel();
    assert!(touched.len() <= 4, "at most four shared files: {touched:?}");
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/ARCHITECTURE.md")).unwrap();
    let section = text.split("### DYNAMIXEL, through the seam").nth(1).expect("the section").split("\n#").next();
    let mut named: Vec<String> = section
        .unwrap_or_default()
        .lines()
        .filter_map(|line| line.strip_prefix("- `")?.split('`').next().map(str::to_string))
        .collect();
    named.sort();
    assert_eq!(touched, named, "the shared edits are the ones ARCHITECTURE.md names");
}
