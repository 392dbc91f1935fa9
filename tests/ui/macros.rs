//! The macro composer (`src/ui/servo/macros.rs`), through egui_kittest.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;
use crate::common::ui::run_until;

use std::path::Path;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::project::{self, Command, Macro, Run, ServoProject};
use servo_studio::ui::{Action, ServoBoardLink as _, StudioApp, Tab};

pub(super) fn fixture() -> ServoProject {
    project::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/project-v1.json")).unwrap().servo
}

pub(super) fn harness(project: ServoProject, tab: Tab) -> Harness<'static, StudioApp> {
    common::ui::showing(common::ui::editor(project), tab, (1300.0, 900.0))
}

#[test]
fn the_composer_shows_command_and_macro_durations() {
    let harness = harness(fixture(), Tab::Macros);
    // Macro 100: 1.00 s + 0.50 s + 1.20 s.
    assert!(harness.query_all_by_label("Total 2.70 s").next().is_some());
    for each in ["1.00 s", "0.50 s", "1.20 s"] {
        assert!(harness.query_by_label(each).is_some(), "{each}");
    }
}

#[test]
fn a_macro_cycle_shows_its_warning_inline() {
    let mut project = fixture();
    project.macros[0].commands.push(Command::once(Run::Macro { macro_id: 101 }));
    let mut harness = harness(project, Tab::Macros);
    // Macro 100 is open: it has no total, because it reaches itself.
    assert!(harness.query_by_label_contains("is part of a cycle").is_some());
    // The cycle is reported at the command that closes it, in macro 101, which the list flags.
    assert!(harness.query_by_label_contains("! 101").is_some(), "the list flags the macro");
    harness.get_by_label_contains("101 打招呼").click();
    harness.run_steps(2);
    assert!(harness.query_by_label_contains("macro cycle 100 → 101 → 100").is_some(), "the warning is inline");
}

#[test]
fn commands_are_added_reordered_and_undone() {
    let mut harness = harness(fixture(), Tab::Macros);
    let original = harness.state().document.project.servo.clone();
    harness.get_by_label("+ Delay").click();
    harness.run_steps(2);
    let commands = &harness.state().document.project.servo.macros[0].commands;
    assert_eq!(commands.len(), 4);
    assert_eq!(commands[3], Command::once(Run::Delay { delay_ms: 500 }));
    // Move the new delay up one place.
    harness.get_all_by_label("↑").nth(2).unwrap().click();
    harness.run_steps(2);
    let commands = &harness.state().document.project.servo.macros[0].commands;
    assert_eq!(commands[2], Command::once(Run::Delay { delay_ms: 500 }));
    harness.state_mut().apply(Action::Undo);
    harness.state_mut().apply(Action::Undo);
    assert_eq!(harness.state().document.project.servo, original);
}

#[test]
fn adding_a_macro_opens_it() {
    let mut harness = harness(ServoProject::default(), Tab::Macros);
    harness.get_by_label("Add macro").click();
    harness.run_steps(2);
    assert_eq!(
        harness.state().document.project.servo.macros,
        [Macro { id: 1, caption: "Macro 1".into(), commands: vec![] }]
    );
}

#[test]
fn drawing_an_invalid_ratio_does_not_silently_change_it() {
    let mut project = fixture();
    project.macros[0].commands[0].ratio_percent = 0;
    let harness = harness(project.clone(), Tab::Macros);
    assert_eq!(harness.state().document.project.servo, project);
    assert!(!harness.state().document.dirty);
    assert!(harness.query_all_by_label_contains("ratio 0 % is outside 1..=100").next().is_some());
}

#[test]
fn a_command_is_dragged_to_a_new_place() {
    let mut harness = harness(fixture(), Tab::Macros);
    let original = harness.state().document.project.servo.macros[0].commands.clone();
    let from = harness.get_by_role_and_label(egui::accesskit::Role::Label, "≡ 3").rect().center();
    let to = harness.get_by_role_and_label(egui::accesskit::Role::Label, "≡ 1").rect().center();
    harness.drag_at(from);
    harness.run_steps(2);
    for step in 1..=10 {
        harness.hover_at(from + (to - from) * (step as f32 / 10.0));
        harness.run_steps(1);
    }
    harness.drop_at(to);
    harness.run_steps(3);
    let commands = &harness.state().document.project.servo.macros[0].commands;
    assert_eq!(commands[0], original[2], "the third command is now first");
    assert_eq!(&commands[1..], &original[..2]);
}

#[test]
fn inline_problems_speak_the_interface_language() {
    let mut project = fixture();
    project.macros[0].commands.push(Command::once(Run::Macro { macro_id: 101 }));
    project.macros[0].commands[0].ratio_percent = 0;
    let mut harness = harness(project, Tab::Macros);
    harness.state_mut().apply(Action::SetLanguage(servo_studio::ui::Language::TraditionalChinese));
    harness.run_steps(2);
    assert!(harness.query_all_by_label_contains("速度比例 0 % 不在 1..=100 之間").next().is_some());
    harness.get_by_label_contains("101 打招呼").click();
    harness.run_steps(2);
    assert!(harness.query_all_by_label_contains("巨集循環 100 → 101 → 100").next().is_some());
}

/// ▶ on a command plays the macro from there: on the board, that command and
/// those after it (nothing before), each at its own speed and loops; the
/// preview's cursor goes to where the command starts.
#[test]
fn play_from_here_sends_the_macro_from_that_command_and_moves_the_preview_there() {
    use servo_studio::link::LinkEvent;
    use servo_studio::protocol::servo::Message;
    use servo_studio::sim::SimEvent;
    use std::time::{Duration, Instant};
    let mut harness = harness(fixture(), Tab::Macros);
    harness.state_mut().apply(Action::ConnectDemo);
    // Until the board is first read, where a servo stands is not known (its first move would be timed from the far end).
    run_until(&mut harness, "the first reading", |app| {
        common::ui::servo_board(app).is_some_and(|board| board.servos_read_at.is_some())
    });
    let events = harness.state().link.as_ref().unwrap().demo_board().unwrap().events().clone();
    // Macro 100: action 1 (1.00 s), a 0.50 s delay, action 2 at 50 % three times.
    harness.get_all_by_label("Play here").nth(2).expect("the third command's Play here").click();
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut sent = Vec::new();
    while sent.len() < 3 {
        assert!(Instant::now() < deadline, "the loops never all played: {sent:?}");
        harness.step();
        common::ui::wait_for_news();
        while let Ok(event) = events.try_recv() {
            if let LinkEvent::Driver(SimEvent::Handled(Message::ExecuteActionRequest { moves })) = event {
                sent.extend(moves.iter().map(|m| (m.servo_id, m.degree, m.interval_10ms)));
            }
        }
    }
    // Nod: servo 3 to 30° over 200 ms, at half speed 400 ms, three times; nothing of action 1.
    assert_eq!(sent, [(3, 30, 40); 3]);
    let t = common::ui::servo_ui(harness.state()).figure.transport.t_ms;
    assert!((1500.0..1510.0).contains(&t), "the preview's cursor at the command's start: {t}");
}
