//! The servo sliders and the app shell, driven through egui_kittest against
//! the in-process emulated board.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::time::{Duration, Instant};

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::link::{LinkEvent, no_waker};
use servo_studio::project::{self, Servo, ServoProject};
use servo_studio::protocol::servo::Message;
use servo_studio::sim::SimEvent;
use servo_studio::ui::{Action, ServoBoardLink as _, StudioApp};

fn project() -> ServoProject {
    let mut left = Servo::new(1, "左肩");
    left.min_deg = -90;
    left.max_deg = 90;
    let mut head = Servo::new(3, "頭部");
    head.min_deg = -45;
    head.max_deg = 45;
    ServoProject { project_id: 7, servos: vec![left, head], ..ServoProject::default() }
}

/// An app whose backups and recovery file go to a fresh folder, not the user's.
fn new_app(project: ServoProject) -> StudioApp {
    let data = tempfile::tempdir().unwrap().keep();
    StudioApp::new(project, None, no_waker()).with_data_dir(data)
}

fn harness(app: StudioApp) -> Harness<'static, StudioApp> {
    // Missing glyphs panic in the harness: the shipped CJK font must cover every caption.
    common::ui::window(app, (1200.0, 700.0))
}

/// The editor connected to the demo board, once the board's first reading of
/// the servos is in (before it, where a servo is cannot be known and a live
/// move is timed from the far end of its limits).
fn demo_harness() -> Harness<'static, StudioApp> {
    let mut app = new_app(project());
    app.apply(Action::ConnectDemo);
    let mut harness = harness(app);
    harness.run();
    common::ui::run_until(&mut harness, "the first reading of the servos", |app| {
        common::ui::servo_board(app).is_some_and(|board| board.servos_read_at.is_some())
    });
    harness
}

/// The live moves the demo board handled, as (servo, degree), waiting (with a
/// deadline) until the board has handled one that puts `servo_id` at `last`.
fn moves_until(harness: &mut Harness<'static, StudioApp>, servo_id: u8, last: i16) -> Vec<(u8, i16)> {
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut moves = Vec::new();
    loop {
        let link = harness.state().link.as_ref().unwrap();
        let event = link.demo_board().unwrap().events().recv_deadline(deadline).expect("the move arrived in time");
        if let LinkEvent::Driver(SimEvent::Handled(Message::ExecuteActionRequest { moves: sent })) = event {
            moves.extend(sent.iter().map(|m| (m.servo_id, m.degree)));
            if sent.iter().any(|m| m.servo_id == servo_id && m.degree == last) {
                return moves;
            }
        }
    }
}

#[test]
fn a_drag_sends_coalesced_live_moves_and_the_last_value_arrives() {
    let mut harness = demo_harness();
    let slider = harness.get_all_by_role(Role::Slider).next().unwrap().rect();
    let y = slider.center().y;
    harness.drag_at(egui::pos2(slider.center().x, y));
    harness.run();
    for step in 1..=20 {
        harness.hover_at(egui::pos2(slider.center().x + slider.width() * 0.02 * step as f32, y));
        harness.run();
    }
    harness.drop_at(egui::pos2(slider.right() + 50.0, y));
    harness.run();
    let last = *common::ui::servo_ui(harness.state()).pose.get(&1).unwrap();
    assert_eq!(last, 90, "dragged past the end: clamped to the servo's max");
    let moves = moves_until(&mut harness, 1, last);
    assert!(!moves.is_empty());
    assert!(moves.iter().all(|(servo, _)| *servo == 1), "{moves:?}");
    let degrees: Vec<i16> = moves.iter().map(|(_, degree)| *degree).collect();
    assert!(degrees.windows(2).all(|pair| pair[0] < pair[1]), "moves follow the drag, never back: {degrees:?}");
    assert!(degrees.len() <= 22, "at most one move per frame: {degrees:?}");
    // Nothing stale after the release: the board ends at the last value.
    arrived(&harness, 90);
}

#[test]
fn keyboard_nudges_the_focused_servo_by_1_and_10() {
    let mut harness = harness(new_app(project()));
    harness.run();
    harness.get_all_by_role(Role::Slider).nth(1).unwrap().focus();
    harness.run();
    harness.key_press(egui::Key::ArrowRight);
    harness.run();
    assert_eq!(common::ui::servo_ui(harness.state()).pose.get(&3), Some(&1));
    harness.key_press_modifiers(egui::Modifiers::SHIFT, egui::Key::ArrowRight);
    harness.run();
    assert_eq!(common::ui::servo_ui(harness.state()).pose.get(&3), Some(&11));
    harness.key_press(egui::Key::PageDown);
    harness.run();
    assert_eq!(common::ui::servo_ui(harness.state()).pose.get(&3), Some(&1));
    for _ in 0..10 {
        harness.key_press(egui::Key::PageUp);
        harness.run();
    }
    assert_eq!(common::ui::servo_ui(harness.state()).pose.get(&3), Some(&45), "the limit holds");
    assert_eq!(common::ui::servo_ui(harness.state()).pose.get(&1), Some(&0), "the other servo did not move");
}

#[test]
fn capture_pose_creates_an_action_and_undo_redo_restore_exact_states() {
    let mut app = new_app(project());
    app.apply(Action::family(servo_studio::ui::ServoAction::SetPose { servo_id: 1, degree: -30 }));
    app.apply(Action::family(servo_studio::ui::ServoAction::SetPose { servo_id: 3, degree: 200 }));
    let mut harness = harness(app);
    harness.run();
    let before = harness.state().document.project.servo.clone();
    harness.get_by_label("Capture pose").click();
    harness.run();
    let after = harness.state().document.project.servo.clone();
    assert_eq!(after.actions.len(), 1);
    let action = &after.actions[0];
    assert_eq!(action.id, 1);
    let steps: Vec<(u8, i16)> = action.steps.iter().map(|s| (s.servo_id, s.degree)).collect();
    assert_eq!(steps, [(1, -30), (3, 45)], "the captured pose, within limits");
    assert_eq!(project::validate_servo(&after), [], "a captured pose is a valid action");

    harness.get_by_label("Undo").click();
    harness.run();
    assert_eq!(harness.state().document.project.servo, before);
    harness.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::Z);
    harness.run();
    assert_eq!(harness.state().document.project.servo, after);
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run();
    assert_eq!(harness.state().document.project.servo, before);
}

#[test]
fn escape_stops_every_servo_holding_torque_and_blocks_moves_until_resume() {
    let mut harness = demo_harness();
    harness.key_press(egui::Key::Escape);
    harness.run();
    let requester = common::ui::servo_board(harness.state()).unwrap().requester();
    // The STOP frame is written ahead of this query, so the query sees it applied.
    let servos = requester.query_servos(1).unwrap();
    assert!(!servos[0].is_start && servos[0].is_hold, "{servos:?}");
    harness.state_mut().apply(Action::family(servo_studio::ui::ServoAction::SetPose { servo_id: 1, degree: 40 }));
    assert!(harness.state().status.as_ref().unwrap().is_error, "moving while stopped is refused");
    harness.get_by_label("Resume").click();
    harness.run();
}

#[test]
fn the_interface_switches_to_traditional_chinese() {
    let mut app = new_app(project());
    app.apply(Action::SetLanguage(servo_studio::ui::Language::TraditionalChinese));
    let mut harness = harness(app);
    harness.run();
    assert!(harness.query_by_label("擷取姿勢").is_some());
    assert!(harness.query_by_label("示範控制板").is_some());
    assert!(harness.query_all_by_label_contains("左肩 #1").next().is_some());
}

#[test]
fn servos_are_added_and_edited_in_the_settings() {
    let mut harness = harness(new_app(project()));
    harness.run();
    harness.get_by_label("Servo settings").click();
    harness.run();
    harness.get_by_label("Add servo").click();
    harness.run();
    let servos = &harness.state().document.project.servo.servos;
    assert_eq!(servos.len(), 3);
    assert_eq!((servos[2].id, servos[2].caption.as_str()), (0, "Servo 0"), "the first free id");
    assert_eq!(harness.get_all_by_role(Role::Slider).count(), 3, "and it gets a slider");
}

#[test]
fn two_separate_drags_of_one_value_are_two_undo_steps() {
    let mut harness = harness(new_app(project()));
    harness.run();
    let original = harness.state().document.project.servo.clone();
    let set_min = |harness: &mut Harness<'static, StudioApp>, min_deg: i16| {
        let mut servo = harness.state().document.project.servo.servos[0].clone();
        servo.min_deg = min_deg;
        harness.state_mut().apply(Action::Edit {
            edit: project::Edit::SetServo { index: 0, servo },
            coalesce: Some("servo 1 min".into()),
        });
    };
    // First drag: three values, one step.
    for min_deg in [-85, -80, -75] {
        set_min(&mut harness, min_deg);
    }
    harness.run(); // pointer up, nothing focused: the step is sealed
    // Second drag of the same value.
    for min_deg in [-70, -60] {
        set_min(&mut harness, min_deg);
    }
    harness.state_mut().apply(Action::Undo);
    assert_eq!(harness.state().document.project.servo.servos[0].min_deg, -75);
    harness.state_mut().apply(Action::Undo);
    assert_eq!(harness.state().document.project.servo, original);
}

#[test]
fn status_messages_follow_the_language() {
    let mut app = new_app(project());
    app.apply(Action::SetLanguage(servo_studio::ui::Language::TraditionalChinese));
    app.apply(Action::ConnectDemo);
    assert!(app.status.as_ref().unwrap().text.starts_with("已連線至示範控制板"), "{:?}", app.status);
    app.apply(Action::Stop);
    assert_eq!(app.status.as_ref().unwrap().text, "停止：所有舵機停在原處並保持鎖定");
}

/// The first live move the demo board handles for `servo_id`: (degree, interval in 10 ms).
fn next_move(harness: &Harness<'static, StudioApp>, servo_id: u8) -> (i16, i16) {
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let link = harness.state().link.as_ref().unwrap();
        let event = link.demo_board().unwrap().events().recv_deadline(deadline).expect("the move arrived in time");
        if let LinkEvent::Driver(SimEvent::Handled(Message::ExecuteActionRequest { moves })) = event
            && let Some(found) = moves.iter().find(|m| m.servo_id == servo_id)
        {
            return (found.degree, found.interval_10ms);
        }
    }
}

/// Waits (with a deadline) until the demo board reports servo 1 at `angle`.
fn arrived(harness: &Harness<'static, StudioApp>, angle: i16) {
    let requester = common::ui::servo_board(harness.state()).unwrap().requester();
    common::ui::servos_until(&requester, &format!("servo 1 at {angle}°"), |servos| {
        servos.iter().any(|servo| servo.servo_id == 1 && servo.angle == angle)
    });
}

/// Clicks servo 1's slider at its far right (`true`) or left end.
fn click_far_end(harness: &mut Harness<'static, StudioApp>, right: bool) {
    let slider = harness.get_all_by_role(Role::Slider).next().unwrap().rect();
    let x = if right { slider.right() - 1.0 } else { slider.left() + 1.0 };
    harness.drag_at(egui::pos2(x, slider.center().y));
    harness.drop_at(egui::pos2(x, slider.center().y));
    harness.run();
}

#[test]
fn a_far_slider_click_reaches_its_angle_at_the_live_speed_limit() {
    let mut harness = demo_harness();
    // A click at the far end: 0° → 90° at the default 180°/s takes 0.5 s, 50 units of 10 ms.
    click_far_end(&mut harness, true);
    assert_eq!(common::ui::servo_ui(harness.state()).pose.get(&1), Some(&90));
    assert_eq!(next_move(&harness, 1), (90, 50));
    arrived(&harness, 90);
    // The Settings menu shows the limit; at 45°/s, 90° → −90° takes 4 s.
    harness.get_by_label("Settings").click();
    harness.run();
    assert_eq!(harness.get_by_label("Live speed limit").value().as_deref(), Some("180 °/s"));
    harness.get_by_label("Settings").click();
    harness.run();
    // What the menu's value sends when set to 45.
    harness.state_mut().apply(Action::SetLiveSpeed(45.0));
    let sent_away = Instant::now();
    click_far_end(&mut harness, false);
    assert_eq!(common::ui::servo_ui(harness.state()).pose.get(&1), Some(&-90));
    // The board reads 90° once within half a degree of it: 179.5°–180° at 45°/s.
    let (degree, interval_10ms) = next_move(&harness, 1);
    assert_eq!(degree, -90);
    assert!((399..=400).contains(&interval_10ms), "{interval_10ms}");
    // Clicked back: the servo has only left 90° for as long as the test took
    // between the two clicks, so the move back counts from where that put it,
    // not from the −90° it was sent to (no faster than 45°/s).
    click_far_end(&mut harness, true);
    let between = sent_away.elapsed();
    let (degree, interval_10ms) = next_move(&harness, 1);
    assert_eq!(degree, 90);
    // At 45°/s the way back takes as long as the way out so far: at most `between`.
    let most_10ms = i16::try_from(between.as_millis() / 10 + 1).unwrap_or(i16::MAX).max(2);
    // (On a machine so slow that the servo got all the way, that is the whole 400.)
    assert!(interval_10ms <= most_10ms, "{interval_10ms} × 10 ms back after {between:?} away (the whole way is 400)");
    arrived(&harness, 90);
    assert!((harness.state().remembered().live_speed.deg_per_s - 45.0).abs() < 1e-9, "remembered between runs");
    // A keyboard nudge is small: at 180°/s, 1° (or the little left of the last
    // move) keeps the board's shortest live move.
    harness.state_mut().apply(Action::SetLiveSpeed(180.0));
    harness.get_all_by_role(Role::Slider).next().unwrap().focus();
    harness.run();
    harness.key_press(egui::Key::ArrowLeft);
    harness.run();
    assert_eq!(next_move(&harness, 1), (89, 2));
}

/// After a macro ran on the board, the editor does not know where it left the
/// servos until the board is read again: a slider click then is timed from
/// the far end of the servo's limits (slow, never a slam); once read, from the
/// reading.
#[test]
fn after_a_macro_ran_on_the_board_a_click_is_timed_from_where_the_servo_could_be() {
    use servo_studio::project::{Action as ProjectAction, Command, Macro, Run, Step};
    use servo_studio::ui::ServoAction;
    let mut project = project();
    project.actions.push(ProjectAction { id: 1, caption: "raise".into(), steps: vec![Step::new(1, 60, 10)] });
    project.macros.push(Macro {
        id: 1,
        caption: "go".into(),
        commands: vec![Command::once(Run::Action { action_id: 1 })],
    });
    let mut app = new_app(project);
    app.apply(Action::ConnectDemo);
    let mut harness = harness(app);
    harness.run();
    let read_after = |harness: &mut Harness<'static, StudioApp>, after: Instant| {
        common::ui::run_until(harness, "a reading", |app| {
            common::ui::servo_board(app).and_then(|board| board.servos_read_at).is_some_and(|at| at > after)
        });
    };
    read_after(&mut harness, Instant::now() - Duration::from_secs(3600));
    // The board raises servo 1 to 60° on its own; at once a click asks for 0°.
    harness.state_mut().apply(Action::family(ServoAction::RunMacro(1)));
    harness.state_mut().apply(Action::family(ServoAction::SetPose { servo_id: 1, degree: 0 }));
    // It could be at either end (±90°): 90° at 180°/s, 0.5 s, not the 20 ms a slider move takes.
    assert_eq!(next_move(&harness, 1), (0, 50));
    arrived(&harness, 0);
    // Run again, and read once the macro is over: the next click counts from the reading.
    harness.state_mut().apply(Action::family(ServoAction::RunMacro(1)));
    arrived(&harness, 60);
    read_after(&mut harness, Instant::now());
    harness.state_mut().apply(Action::family(ServoAction::SetPose { servo_id: 1, degree: 30 }));
    // 60° → 30° at 180°/s: 1/6 s, 17 units.
    assert_eq!(next_move(&harness, 1), (30, 17));
}

/// Recording a scripted sequence of slider moves: after the 3 s count-in
/// servo 1 ramps to 60° in 2 s and holds; Stop fits it into one step — an
/// action in which servo 1 arrives early and holds — and a macro running it,
/// one undo step.
#[test]
fn recording_slider_moves_fits_them_into_actions_and_a_macro() {
    use servo_studio::ui::ServoAction;
    let mut harness = harness(new_app(project()));
    harness.run();
    let actions_before = harness.state().document.project.servo.actions.len();
    common::ui::record_through_count_in(&mut harness);
    for k in 0..=8 {
        harness.state_mut().apply(Action::family(ServoAction::SetPose { servo_id: 1, degree: 15 * k / 2 }));
        harness.step();
    }
    for _ in 0..4 {
        harness.step();
    }
    harness.get_by_label("■ Stop recording").click();
    harness.step();
    harness.step();
    let servo = &harness.state().document.project.servo;
    let added = &servo.actions[actions_before..];
    let steps: Vec<(u8, i16, i16)> =
        added.iter().flat_map(|action| action.steps.iter().map(|s| (s.servo_id, s.degree, s.interval_10ms))).collect();
    // One step: servo 1 ramps to 60° (7.5° × 8) on its own interval of about
    // 2 s and holds there while servo 3, at 0 throughout, paces the step to
    // the recording's end (a step lasts as long as its latest servo).
    assert_eq!(added.len(), 1, "{steps:?}");
    assert_eq!((steps[0].0, steps[0].1), (1, 60), "{steps:?}");
    assert!((steps[0].2 - 200).abs() <= 5, "{steps:?}");
    assert_eq!((steps[1].0, steps[1].1), (3, 0), "{steps:?}");
    assert!(steps[1].2 > steps[0].2 + 50, "servo 1 arrives early and holds: {steps:?}");
    let recorded = servo.macros.last().unwrap();
    let runs: Vec<i32> = recorded
        .commands
        .iter()
        .map(|command| match command.run {
            project::Run::Action { action_id } => action_id,
            _ => 0,
        })
        .collect();
    assert_eq!(runs, added.iter().map(|action| action.id).collect::<Vec<_>>(), "the macro runs them in order");
    let status = harness.state().status.as_ref().unwrap().text.clone();
    assert!(status.contains("→ 1 action, run by macro"), "one action, said as one: {status}");
    harness.state_mut().apply(Action::Undo);
    harness.step();
    assert_eq!(harness.state().document.project.servo.actions.len(), actions_before, "one undo step");
}
