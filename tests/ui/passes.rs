//! A record pass on the open project is an edit of it: one step of the
//! editor's own Undo (Ctrl+Z) and Redo, seen among the project's macros;
//! undone, the show, its cue and the log line that said it go back too; and
//! a pass starts from where its axis is, never from a value another axis left.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use servo_studio::show::Start;
use servo_studio::show::passes::Axis;
use servo_studio::ui::show::ShowAction;
use servo_studio::ui::{Action, StudioApp, Tab};

/// Records a pass of the picked axis from the show's start, the hand moving
/// it by `hand` (degrees at seconds) each frame, until `until_ms` on the show's clock.
fn record(harness: &mut Harness<'static, StudioApp>, until_ms: u64, hand: impl Fn(f64) -> f64) {
    harness.state_mut().desks.show.stage.scrub_ms = 0;
    harness.state_mut().apply(Action::Show(ShowAction::RecordPass(true)));
    harness.step();
    assert!(harness.state().desks.show.passes.recording.is_some(), "recording");
    while harness.state().desks.show.stage.scrub_ms < until_ms {
        // Whole ms of a show: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let t = harness.state().desks.show.stage.scrub_ms as f64 / 1000.0;
        harness.state_mut().desks.show.passes.value = hand(t);
        harness.step();
        common::ui::wait_for_news();
    }
    harness.get_by_label("■ Stop pass").click();
    harness.run_steps(3);
}

fn macros(app: &StudioApp) -> Vec<String> {
    app.document.project.servo.macros.iter().map(|each| each.caption.clone()).collect()
}

fn show_macros(app: &StudioApp) -> usize {
    app.desks.show.session.as_ref().unwrap().show.devices[0].project.servo.macros.len()
}

#[test]
fn a_pass_on_the_open_project_is_one_step_of_the_editors_undo_and_redo() {
    let mut app = common::ui::editor(servo_studio::ui::sample_project());
    app.apply(Action::Show(ShowAction::OpenProject));
    let mut harness = common::ui::showing(app, Tab::Macros, (1280.0, 800.0));
    let before = macros(harness.state());
    let cues_before = harness.state().desks.show.session.as_ref().unwrap().show.cues.len();
    assert!(!harness.state().document.can_undo());
    harness.state_mut().desks.show.passes.pick("board", Axis::Servo(1));
    harness.run_steps(2);
    record(&mut harness, 1200, |t| 20.0 * t);

    // The project has the macro the pass made: one undo step, seen among the macros.
    let after = macros(harness.state());
    assert_eq!(after.len(), before.len() + 1, "{after:?}");
    assert_eq!(after.last().unwrap(), "Recorded passes");
    assert!(harness.state().document.can_undo() && harness.state().document.dirty);
    assert!(harness.query_all_by_label_contains("Recorded passes").next().is_some(), "the Macros tab lists it");
    let session = harness.state().desks.show.session.as_ref().unwrap();
    let made = harness.state().document.project.servo.macros.last().unwrap().id;
    assert!(session.show.cues.iter().any(|cue| cue.device == "board" && cue.start == Start::Macro(made)), "cued");
    assert_eq!(show_macros(harness.state()), after.len(), "the show's device is the project");
    let joined_line = common::ui::show_log(harness.state()).join("\n");
    assert!(joined_line.contains("board: 1 pass joined"), "{joined_line}");
    assert!(harness.query_by_label("Undo pass").is_some_and(|button| !button.accesskit_node().is_disabled()));

    // Ctrl+Z: the project, the show's device, its cue and the log line go back, at once.
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run_steps(3);
    assert_eq!(macros(harness.state()), before, "the editor's Undo took the pass back");
    assert_eq!(show_macros(harness.state()), before.len());
    assert_eq!(harness.state().desks.show.session.as_ref().unwrap().show.cues.len(), cues_before);
    assert!(
        !common::ui::show_log(harness.state()).iter().any(|line| line.contains("joined")),
        "the line saying it was joined is gone: {:?}",
        common::ui::show_log(harness.state())
    );
    assert!(harness.query_all_by_label_contains("Recorded passes").next().is_none(), "gone from the Macros tab");
    assert!(!harness.state().document.can_undo());

    // Redo brings it all again.
    harness.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::Z);
    harness.run_steps(3);
    assert_eq!(macros(harness.state()), after);
    assert_eq!(show_macros(harness.state()), after.len());
    assert!(common::ui::show_log(harness.state()).iter().any(|line| line.contains("1 pass joined")));

    // An edit of the project after it: Undo takes that back first, and the show window's Undo pass waits.
    harness.state_mut().apply(Action::SetLiveSpeed(90.0));
    let mut servo = harness.state().document.project.servo.clone();
    servo.servos[0].caption.push('!');
    harness
        .state_mut()
        .apply(Action::Edit { edit: servo_studio::project::Edit::ReplaceAll(Box::new(servo)), coalesce: None });
    harness.run_steps(2);
    assert!(harness.query_by_label("Undo pass").is_some_and(|button| button.accesskit_node().is_disabled()));
    harness.state_mut().apply(Action::Show(ShowAction::UndoPass));
    assert_eq!(macros(harness.state()), after, "Undo pass does not undo an edit that is not a pass");
    harness.state_mut().apply(Action::Undo);
    harness.state_mut().apply(Action::Show(ShowAction::UndoPass));
    harness.run_steps(2);
    assert_eq!(macros(harness.state()), before, "then the pass");

    // Closed, the show takes its steps along; what it made of the project stays an edit of it.
    harness.state_mut().apply(Action::Redo);
    harness.state_mut().apply(Action::Show(ShowAction::Close));
    assert_eq!(macros(harness.state()), after);
    harness.state_mut().apply(Action::Undo);
    assert_eq!(macros(harness.state()), before, "the project's step outlived the show");
}

#[test]
fn a_pass_starts_where_its_axis_is_not_where_another_axis_was_left() {
    let mut app = common::ui::editor(servo_studio::ui::sample_project());
    app.apply(Action::Show(ShowAction::OpenProject));
    let mut harness = common::ui::showing(app, Tab::Servos, (1280.0, 800.0));
    // Servo 2 picked and moved by hand to −26°, never recorded.
    harness.state_mut().desks.show.passes.pick("board", Axis::Servo(2));
    harness.run_steps(2);
    harness.state_mut().desks.show.passes.value = -26.0;
    harness.run_steps(2);
    // Servo 1 picked; Record pressed without touching its slider.
    harness.state_mut().desks.show.passes.pick("board", Axis::Servo(1));
    harness.state_mut().apply(Action::Show(ShowAction::RecordPass(true)));
    harness.step();
    let show = harness.state().desks.show.session.as_ref().unwrap().show.clone();
    let posed = servo_studio::show::timeline::posed_at(&show, 0, 0).unwrap();
    let servo_1 = servo_studio::show::at::axis_value(&posed, Axis::Servo(1)).unwrap();
    assert!((servo_1 - -26.0).abs() > 1.0, "the test needs servo 1 away from −26°: {servo_1}");
    harness.step();
    let pass = harness.state().desks.show.passes.recording.clone().expect("recording");
    let first = pass.samples.first().expect("a sample").1;
    assert!((first - servo_1).abs() < 1e-9, "the pass starts where servo 1 is ({servo_1}°), not at {first}°");
    // A value the hand set after picking is kept: the pass starts there.
    harness.state_mut().apply(Action::Show(ShowAction::RecordPass(false)));
    harness.state_mut().desks.show.passes.value = 12.5;
    harness.state_mut().desks.show.stage.scrub_ms = 0;
    harness.state_mut().apply(Action::Show(ShowAction::RecordPass(true)));
    harness.step();
    let pass = harness.state().desks.show.passes.recording.clone().expect("recording");
    assert_eq!(pass.samples.first().map(|sample| sample.1), Some(12.5));
}
