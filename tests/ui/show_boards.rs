//! A show's boards held by the editor (**Connect the boards**): two servo
//! boards, a PLEN2 and an rFLEX base on four emulators, each logging what it
//! receives. Every device says it answered; while they are held the preview
//! and a record pass play on every board at once (the pass's servo where
//! the hand has it, the others on their cues, the base on its drive); STOP
//! stops them all (the base brakes); Play on the boards uses the held
//! links; a lost link the show needs stops every device and the preview.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Duration;

use egui_kittest::kittest::Queryable;
use servo_studio::project::{Family, Project};
use servo_studio::show::passes::Axis;
use servo_studio::show::{Cue, Show, Start};
use servo_studio::ui::Tab;
use servo_studio::ui::show::ShowAction;

use crate::cli::play::{Stage, device, logged_until, swinging, waving};
use crate::common;

type Harness = egui_kittest::Harness<'static, servo_studio::ui::StudioApp>;

const LONG: Duration = Duration::from_secs(30);

/// Two servo boards swinging, a PLEN2 waving and a base driving, all from 0.
fn four_devices() -> Show {
    let cue = |device: &str, start| Cue { device: device.into(), at_ms: 0, start };
    Show {
        devices: vec![
            device("skull", swinging(400)),
            device("arms", swinging(400)),
            device("plen", waving()),
            device("base", Project::empty(Family::Rflex)),
        ],
        sound: None,
        cues: vec![
            cue("skull", Start::Macro(1)),
            cue("arms", Start::Macro(1)),
            cue("plen", Start::Slot(2)),
            cue("base", Start::Drive { speed_m_s: 0.1, turn_deg_s: 0.0, for_ms: 120_000 }),
        ],
    }
}

/// The show open with every emulator's port typed, its boards connected and every device answered.
fn connected(stage: &Stage) -> Harness {
    let mut app = common::ui::editor(Project::servo(common::sample_biped()));
    app.apply(servo_studio::ui::Action::Show(ShowAction::Open(stage.dir.path().join("show.json"))));
    let session = app.desks.show.session.as_mut().expect("the show opened");
    session.ports = stage.device_args().chunks(2).map(|pair| pair[1].split_once('=').unwrap().1.to_string()).collect();
    let mut harness = common::ui::showing(app, Tab::Servos, (1280.0, 2000.0));
    harness.get_by_label("Connect the boards").click();
    common::ui::run_until(&mut harness, "every device answered", |app| {
        app.desks.show.linked.as_ref().is_some_and(servo_studio::ui::show::Linked::all_answered)
    });
    assert_eq!(harness.query_all_by_label_contains("● answered").count(), stage.sims.len(), "a state per device");
    harness
}

/// The log's lines after its first `from` lines.
fn lines_after(stage: &Stage, name: &str, from: usize) -> Vec<String> {
    let text = std::fs::read_to_string(stage.log(name)).unwrap_or_default();
    text.lines().skip(from).map(str::to_string).collect()
}

fn line_count(stage: &Stage, name: &str) -> usize {
    std::fs::read_to_string(stage.log(name)).unwrap_or_default().lines().count()
}

#[test]
fn held_boards_follow_a_record_pass_together_and_stop_stops_them_all() {
    let stage = Stage::new(&four_devices(), &[]);
    let mut harness = connected(&stage);
    let before: Vec<usize> = ["skull", "arms", "plen", "base"].iter().map(|n| line_count(&stage, n)).collect();
    harness.state_mut().desks.show.passes.pick("skull", Axis::Servo(1));
    harness.state_mut().desks.show.passes.value = 25.0;
    // A frame to draw the pass's row as picked, then a click.
    harness.run_steps(2);
    harness.get_by_label("● Record pass").click();
    // The pass's servo goes where the hand has it; every other board plays its part.
    let wait = |harness: &mut Harness, name: &str, from: usize, wanted: &dyn Fn(&str) -> bool| {
        let deadline = std::time::Instant::now() + LONG;
        while !lines_after(&stage, name, from).iter().any(|line| wanted(line)) {
            assert!(
                std::time::Instant::now() < deadline,
                "{name} never received it: {:?}",
                lines_after(&stage, name, from)
            );
            harness.step();
            common::ui::wait_for_news();
        }
    };
    wait(&mut harness, "skull", before[0], &|line| line.contains("degree: 25"));
    wait(&mut harness, "arms", before[1], &|line| line.contains("degree: -") || line.contains("degree: 3"));
    wait(&mut harness, "plen", before[2], &|line| line.contains("$AN") || line.contains("SetAngle"));
    // Driven forward (axis 0, the translation) at its cue's speed, the brake let go.
    wait(&mut harness, "base", before[3], &|line| line.contains("AxisSetDir { axis: 0") && !line.contains("speed: 0,"));
    assert!(lines_after(&stage, "base", before[3]).iter().any(|line| line.contains("BrakeRelease")));
    assert!(harness.state().desks.show.stage.previewing());
    let stopping: Vec<usize> = ["skull", "arms", "plen", "base"].iter().map(|n| line_count(&stage, n)).collect();
    harness.get_by_label("■ STOP").click();
    harness.run_steps(2);
    assert!(!harness.state().desks.show.stage.previewing(), "STOP ends the pass");
    wait(&mut harness, "skull", stopping[0], &|line| line.contains("is_start: false"));
    wait(&mut harness, "arms", stopping[1], &|line| line.contains("is_start: false"));
    wait(&mut harness, "plen", stopping[2], &|line| line.contains("#RI") || line.contains("ResetInterpreter"));
    wait(&mut harness, "base", stopping[3], &|line| line.contains("BrakeSet"));
}

#[test]
fn the_show_plays_on_the_held_boards_and_a_lost_link_stops_every_following_device() {
    let show =
        Show { devices: four_devices().devices[..2].to_vec(), cues: four_devices().cues[..2].to_vec(), sound: None };
    let mut short = show.clone();
    short.devices.iter_mut().for_each(|device| device.project = swinging(2));
    let stage = Stage::new(&short, &[]);
    let mut harness = connected(&stage);
    harness.get_by_label("Play on the boards").click();
    common::ui::run_until(&mut harness, "the show ended", |app| {
        !app.desks.show.playing() && common::ui::show_log(app).iter().any(|line| line.starts_with("ended after"))
    });
    logged_until(stage.log("skull"), "ExecuteMacroRequest", LONG);
    logged_until(stage.log("arms"), "ExecuteMacroRequest", LONG);
    // The links are still held: the preview follows on them, until one is lost.
    harness.get_by_label("Preview").click();
    harness.run_steps(2);
    let mut stage = stage;
    let (_, mut gone, _) = stage.sims.remove(1);
    gone.child.kill().unwrap();
    gone.child.wait().unwrap();
    common::ui::run_until(&mut harness, "the lost link said", |app| {
        common::ui::show_log(app).iter().any(|line| line.contains("arms link lost"))
    });
    let said = common::ui::show_log(harness.state()).join("\n");
    assert!(said.contains("every device was stopped"), "{said}");
    assert!(!harness.state().desks.show.stage.previewing(), "the preview stopped with the boards");
    logged_until(stage.log("skull"), "is_start: false", LONG);
    assert!(harness.query_by_label_contains("link lost:").is_some(), "the device's row says so");
}
