//! File → Import from another tool…: the file read off the frame, the joint
//! map guessed and edited in the table while the figure plays it, Create
//! adding everything as one undo step, the map saved and loaded again.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::float_cmp)]

use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use egui::accesskit::Role;
use egui_kittest::kittest::{Queryable, by};
use servo_studio::project::{Family, Project, Run, ServoProject};
use servo_studio::ui::{Action, FileRequest, Picker, Tab};

use crate::common;

/// A picker answering every request with the next of `answers`.
fn picker(answers: Vec<PathBuf>) -> Picker {
    let answers = Arc::new(Mutex::new(answers));
    Arc::new(move |_: &FileRequest, waker: servo_studio::link::Waker| {
        let (tx, rx) = crossbeam_channel::bounded(1);
        let next = answers.lock().unwrap().drain(..1).next();
        tx.send(next).unwrap();
        waker();
        rx
    })
}

fn mine() -> ServoProject {
    let mut project = common::sample_biped();
    project.actions.clear();
    project.macros.clear();
    project
}

#[test]
fn a_maestro_file_is_mapped_previewed_and_created_as_one_undo_step() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("skull.xml");
    std::fs::write(&file, crate::interchange::maestro::SETTINGS).unwrap();
    let map_file = dir.path().join("skull.map.json");
    let app =
        common::ui::editor(Project::servo(mine())).with_picker(picker(vec![file, map_file.clone(), map_file.clone()]));
    let mut harness = common::ui::showing(app, Tab::Servos, (1280.0, 800.0));
    harness.get_by_label("File").click();
    harness.run();
    harness.get_by_label("Import from another tool…").click();
    common::ui::run_until(&mut harness, "the file read", |app| app.desks.import.session.is_some());
    // The guessed map: channel 0 "jaw 下巴" drives servo 0, the output channel is not there.
    harness.get_by_label("jaw 下巴");
    assert!(harness.query_all(by().role(Role::ComboBox).value("servo 0")).next().is_some());
    let session = harness.state().desks.import.session.as_ref().unwrap();
    assert_eq!(session.map.entries.len(), 3);
    // The preview at 1.05 s: the jaw half way to +30° (15.0°) in the Now column.
    harness.state_mut().desks.import.session.as_mut().unwrap().time_ms = 1050.0;
    harness.run();
    assert!(harness.query_by_label("15.0").is_some(), "the jaw's angle at the preview's time");
    // The eye is not imported: picked in its row's Drives list.
    harness.query_all(by().role(Role::ComboBox).value("servo 3")).next().unwrap().click();
    harness.run();
    harness.get_by_label("— not imported").click();
    harness.run();
    assert_eq!(harness.state().desks.import.session.as_ref().unwrap().map.entries[2].target, None);
    // Saved, then loaded again (the picker answers the same file).
    harness.get_by_label("Save map…").click();
    common::ui::run_until(&mut harness, "the map saved", |_| map_file.exists());
    let saved = servo_studio::interchange::JointMap::from_json(&std::fs::read_to_string(&map_file).unwrap()).unwrap();
    assert_eq!(saved.entries[2].target, None);
    // A change made after saving is undone by loading the saved map.
    harness.state_mut().desks.import.session.as_mut().unwrap().map.entries[0].offset_deg = 5.0;
    harness.get_by_label("Load map…").click();
    common::ui::run_until(&mut harness, "the map loaded", |app| {
        !app.desks.import.busy() && app.desks.import.session.as_ref().unwrap().map.entries[0].offset_deg == 0.0
    });
    let before = harness.state().document.project.clone();
    harness.get_by_label("Create").click();
    common::ui::run_until(&mut harness, "the import made", |app| !app.document.project.servo.macros.is_empty());
    let servo = &harness.state().document.project.servo;
    assert_eq!(servo.macros.len(), 2, "a macro per sequence");
    assert!(servo.actions.iter().all(|a| a.steps.iter().all(|s| s.servo_id != 3)), "the eye was left out");
    let talk = servo.macros.iter().find(|m| m.caption == "talk").unwrap();
    assert!(matches!(talk.commands[0].run, Run::Action { .. }));
    assert!(harness.query_by_label("Imported").is_some(), "the report is shown");
    assert!(harness.state().status.as_ref().unwrap().text.starts_with("Imported: "));
    harness.get_by_label("Close").click();
    harness.run();
    assert!(harness.state().desks.import.session.is_none());
    harness.state_mut().apply(Action::Undo);
    assert_eq!(harness.state().document.project, before, "one undo step takes the whole import back");
}

#[test]
fn a_roboplus_page_previews_on_the_plen2_figure_and_lands_in_free_slots() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bow.mtn");
    std::fs::write(&file, crate::interchange::robotis::mtn("1.0")).unwrap();
    let mut project = Project::empty(Family::Plen2);
    project.plen2.motions.push(servo_studio::project::plen2::Motion {
        slot: 0,
        name: "mine".into(),
        frames: vec![servo_studio::project::plen2::Frame::new(320, Default::default())],
        loop_range: None,
        jump_slot: None,
    });
    let mut app = common::ui::editor(project);
    app.apply(Action::Import(servo_studio::ui::import::ImportAction::Read(file)));
    let mut harness = common::ui::showing(app, Tab::Motions, (1280.0, 800.0));
    common::ui::run_until(&mut harness, "the file read", |app| app.desks.import.session.is_some());
    // Id 1 shows as the right shoulder (the table's first row); id 13 is guessed as the right knee.
    assert!(harness.query_all(by().role(Role::ComboBox).value("right_shoulder_pitch")).next().is_some());
    let map = &harness.state().desks.import.session.as_ref().unwrap().map;
    let knee = servo_studio::interchange::Target::Joint(servo_studio::project::plen2::Joint::RightKneePitch);
    assert_eq!(map.entry("13").unwrap().target, Some(knee));
    harness.get_by_label("Create").click();
    common::ui::run_until(&mut harness, "the import made", |app| app.document.project.plen2.motions.len() > 1);
    let motions = &harness.state().document.project.plen2.motions;
    assert_eq!(
        motions.iter().map(|m| (m.slot, m.name.as_str())).collect::<Vec<_>>(),
        [(0, "mine"), (1, "Bow"), (2, "Walk"), (3, "Rest")]
    );
    assert_eq!(motions[1].jump_slot, Some(2), "the jump follows the motion to its new slot");
}

#[test]
fn a_servo_project_is_exported_for_a_maestro_and_a_plen2_motion_for_blender() {
    let dir = tempfile::tempdir().unwrap();
    // A servo project made from the Maestro file, written back from the editor.
    let source = servo_studio::interchange::read(
        servo_studio::interchange::Format::Maestro,
        crate::interchange::maestro::SETTINGS,
    )
    .unwrap();
    let map = servo_studio::interchange::JointMap::for_source(&source, Family::Servo, None);
    let built = servo_studio::interchange::build::build(
        &source,
        &map,
        &servo_studio::interchange::build::Options::new(Family::Servo),
    )
    .unwrap();
    let out = dir.path().join("skull.maestro.xml");
    let app = common::ui::editor(built.project).with_picker(picker(vec![out.clone()]));
    let mut harness = common::ui::showing(app, Tab::Servos, (1280.0, 800.0));
    harness.get_by_label("File").click();
    harness.run();
    harness.get_by_label("Export for another tool…").click();
    harness.run();
    assert!(harness.query_all(by().role(Role::ComboBox).value("Maestro settings file (sequences)")).next().is_some());
    harness.get_by_label("Export…").click();
    common::ui::run_until(&mut harness, "the file written", |app| !app.desks.import.busy() && out.exists());
    let written = servo_studio::interchange::read(
        servo_studio::interchange::Format::Maestro,
        &std::fs::read_to_string(&out).unwrap(),
    )
    .unwrap();
    assert_eq!(written.clips.iter().map(|c| c.name.as_str()).collect::<Vec<_>>(), ["talk", "blink"]);
    assert!(
        harness
            .state()
            .status
            .as_ref()
            .unwrap()
            .text
            .starts_with(&format!("Exported {}: 3 channels, 2 sequences, 5 frames", out.display()))
    );
    // A PLEN2 motion as Blender JSON.
    let mut project = Project::empty(Family::Plen2);
    let mut pose = servo_studio::project::plen2::Pose::default();
    pose.set(servo_studio::project::plen2::Joint::LeftKneePitch, 300);
    project.plen2.motions.push(servo_studio::project::plen2::Motion {
        slot: 4,
        name: "kneel".into(),
        frames: vec![servo_studio::project::plen2::Frame::new(320, pose)],
        loop_range: None,
        jump_slot: None,
    });
    let out = dir.path().join("kneel.json");
    let mut app = common::ui::editor(project).with_picker(picker(vec![out.clone()]));
    app.apply(Action::Import(servo_studio::ui::import::ImportAction::OpenExport));
    let mut harness = common::ui::showing(app, Tab::Motions, (1280.0, 800.0));
    assert!(harness.query_all(by().role(Role::ComboBox).value("4 kneel")).next().is_some(), "the motion offered");
    harness.get_by_label("Export…").click();
    common::ui::run_until(&mut harness, "the file written", |app| !app.desks.import.busy() && out.exists());
    let written = servo_studio::interchange::read(
        servo_studio::interchange::Format::Blender,
        &std::fs::read_to_string(&out).unwrap(),
    )
    .unwrap();
    assert_eq!(written.channels.len(), 18);
    let servo_studio::interchange::Body::Samples { rows, .. } = &written.clips[0].body else { panic!("samples") };
    let knee = written.channels.iter().position(|c| c.name == "left_knee_pitch").unwrap();
    let map = servo_studio::interchange::JointMap::for_source(&written, Family::Plen2, None);
    let last = map.entries[knee].degrees(rows.last().unwrap()[knee]);
    assert!((last - 30.0).abs() < 0.2, "the knee ends at 30°: {last}");
}
