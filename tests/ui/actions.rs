//! The action editor: editing steps, the timeline, play on board and preview.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::path::Path;
use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::project::{self, ServoProject, Step};
use servo_studio::ui::{Action, ServoBoardLink as _, StudioApp, Tab};

fn fixture() -> ServoProject {
    project::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/project-v1.json")).unwrap().servo
}

fn harness(project: ServoProject) -> Harness<'static, StudioApp> {
    common::ui::showing(common::ui::editor(project), Tab::Actions, (1300.0, 900.0))
}

#[test]
fn the_timeline_has_a_bar_per_step_and_steps_can_be_added() {
    let mut harness = harness(fixture());
    // Action 1 "舉手": servo 1 to -90° over 500 ms, servo 2 to 45° over 1000 ms; all start at 0.
    let bars = servo_studio::ui::timeline_bars(&harness.state().document.project.servo.actions[0]);
    assert_eq!(bars, [(1, 0.0, 500.0), (2, 0.0, 1000.0)]);
    harness.get_by_label("Add step").click();
    harness.run_steps(2);
    let steps = &harness.state().document.project.servo.actions[0].steps;
    assert_eq!(steps.len(), 3);
    assert_eq!(steps[2], Step::new(3, 0, 50), "the unused servo, at home");
}

#[test]
fn preview_moves_the_sliders_along_the_action_without_a_board() {
    let mut harness = harness(fixture());
    harness.get_by_label("Preview").click();
    harness.run_steps(1);
    let (_, started) = common::ui::servo_ui(harness.state()).preview.unwrap();
    // Half-way through servo 1's 500 ms move from home 0° to -90°.
    harness.state_mut().advance(started + Duration::from_millis(250));
    assert_eq!(common::ui::servo_ui(harness.state()).pose.get(&1), Some(&-45));
    harness.state_mut().advance(started + Duration::from_millis(1000));
    assert_eq!(common::ui::servo_ui(harness.state()).pose.get(&1), Some(&-90));
    assert_eq!(common::ui::servo_ui(harness.state()).pose.get(&2), Some(&45));
    assert!(common::ui::servo_ui(harness.state()).preview.is_none(), "the preview ends after the last step");
}

#[test]
fn play_on_board_moves_the_emulated_servos() {
    let mut harness = harness(fixture());
    harness.state_mut().apply(Action::ConnectDemo);
    harness.run_steps(2);
    harness.get_by_label("Play on board").click();
    harness.run_steps(2);
    let requester = common::ui::servo_board(harness.state()).unwrap().requester();
    common::ui::servos_until(&requester, "the action's angles", |servos| {
        let angle = |id: u8| servos.iter().find(|s| s.servo_id == id).map(|s| s.angle);
        angle(1) == Some(-90) && angle(2) == Some(45)
    });
}

#[test]
fn an_out_of_range_degree_is_flagged_not_silently_changed_and_undoable() {
    let mut harness = harness(fixture());
    let before = harness.state().document.project.servo.clone();
    let mut changed = before.actions[0].clone();
    changed.steps[0].degree = -200; // outside servo 1's -90..90
    harness
        .state_mut()
        .apply(Action::Edit { edit: project::Edit::SetAction { index: 0, action: changed }, coalesce: None });
    harness.run_steps(2);
    assert!(
        harness.query_all_by_label_contains("outside servo 1's limits").next().is_some(),
        "the problem shows inline"
    );
    // Drawing the out-of-range value does not silently "fix" the document.
    assert_eq!(harness.state().document.project.servo.actions[0].steps[0].degree, -200);
    harness.state_mut().apply(Action::Undo);
    assert_eq!(harness.state().document.project.servo, before);
}

#[test]
fn an_actions_steps_are_retimed_together() {
    let mut harness = harness(fixture());
    let intervals = |harness: &Harness<'static, StudioApp>| -> Vec<i16> {
        harness.state().document.project.servo.actions[0].steps.iter().map(|step| step.interval_10ms).collect()
    };
    let before = intervals(&harness);
    assert_eq!(before, vec![50, 100], "500 ms and 1 s");
    harness.get_by_label("×0.5").click();
    harness.run();
    assert_eq!(intervals(&harness), vec![25, 50], "both steps, so the action keeps its shape");
    harness.state_mut().apply(Action::Undo);
    harness.run();
    assert_eq!(intervals(&harness), before);
}

/// The sample robot's rig names each left servo's twin: Mirror L/R turns the
/// right-arm wave into a left-arm wave, each joint turned as the mirror image
/// of its twin's link, one undo step.
#[test]
fn mirror_hands_each_step_to_its_twin_reflected_about_home() {
    let mut servo = common::sample_biped();
    // A twin straight at 10°: the mirror image is of the link, not of the number.
    servo.servos.iter_mut().find(|s| s.id == 2).unwrap().rig.as_mut().unwrap().straight_deg = 10;
    let wave = servo.actions.iter().position(|action| action.id == 2).unwrap();
    servo.actions.swap(0, wave);
    let mut harness = harness(servo);
    let steps = |harness: &Harness<'static, StudioApp>| -> Vec<(u8, i16)> {
        let mut steps: Vec<(u8, i16)> =
            harness.state().document.project.servo.actions[0].steps.iter().map(|s| (s.servo_id, s.degree)).collect();
        steps.sort_unstable();
        steps
    };
    let before = steps(&harness);
    assert_eq!(&before[..6], &[(1, 0), (2, 0), (3, 0), (4, -80), (5, 60), (6, -45)]);
    harness.get_by_label("Mirror L/R").click();
    harness.run();
    // Pitches (shoulder 4 → 1, elbow 6 → 3) keep their sense: the left arm rises as the right did.
    // Shoulder roll 5 is reversed, 2 is not: 5's 60° turns its link −60° about x; the mirror
    // image turns 2's link +60°, from its straight 10°: 70°. Back the other way, 2's 0° is its
    // link at −10°; mirrored +10°, reversed on 5: −10°.
    assert_eq!(&steps(&harness)[..6], &[(1, -80), (2, 70), (3, -45), (4, 0), (5, -10), (6, 0)]);
    assert_eq!(steps(&harness)[6..], before[6..], "the legs' twins hold 0 both sides");
    harness.state_mut().apply(Action::Undo);
    harness.run();
    assert_eq!(steps(&harness), before);
}

/// Checked on the rig's own geometry, not on the formula: the sample robot
/// posed with its right-arm wave and with that wave mirrored puts every
/// left arm link where the right one was, reflected through the body's
/// middle (y → −y), turned as its mirror image.
#[test]
fn a_mirrored_pose_is_the_mirror_image_of_the_robot() {
    use servo_studio::figure::{Mat3, Vec3, rig};
    use std::collections::BTreeMap;
    let servo = common::sample_biped();
    let wave = servo.action(2).unwrap();
    let right: Vec<Step> = wave.steps.iter().filter(|step| (4..=6).contains(&step.servo_id)).copied().collect();
    let left = servo.mirrored(&right);
    let (chain, index_of) = rig::chain(&servo);
    let placed = |steps: &[Step]| {
        let degrees: BTreeMap<u8, f64> = steps.iter().map(|step| (step.servo_id, f64::from(step.degree))).collect();
        chain.pose(&rig::angles(&servo, &index_of, &degrees, chain.links.len()))
    };
    let (right_pose, left_pose) = (placed(&right), placed(&left));
    let flip = Mat3::from_diagonal(Vec3::new(1.0, -1.0, 1.0));
    for (right_id, left_id) in [(4u8, 1u8), (5, 2), (6, 3)] {
        let (r, l) = (&right_pose[index_of[&right_id]], &left_pose[index_of[&left_id]]);
        let reflected = flip * r.position;
        assert!((l.position - reflected).length() < 0.5, "servo {left_id}'s joint at {} for {reflected}", l.position);
        // A link's axes reflected: the mirror image of its frame, its y column flipped back.
        let image = flip * r.rotation * flip;
        assert!(l.rotation.abs_diff_eq(image, 1e-3), "servo {left_id}: {} vs {image}", l.rotation);
    }
}

/// A step's curve is picked in its row (one undo step); the editor then says
/// what the curves cost on the board, and Play on board sends the curve as
/// straight sub-steps, one after another, from where the servo is.
#[test]
fn a_curve_picked_for_a_step_shows_its_cost_and_plays_on_the_board_as_sub_steps() {
    use servo_studio::link::LinkEvent;
    use servo_studio::project::Easing;
    use servo_studio::protocol::servo::Message;
    use servo_studio::sim::SimEvent;
    let mut harness = harness(fixture());
    harness.state_mut().apply(Action::ConnectDemo);
    // The meter says the board's memory once the board has told it (its reply comes on its own thread).
    common::ui::run_until(&mut harness, "the board's memory", |app| {
        common::ui::servo_board(app).is_some_and(|board| board.memory.is_some())
    });
    assert!(harness.query_by_label_contains("On the board:").is_none(), "no curves, no meter");
    let curve = harness.query_all(egui_kittest::kittest::by().value("Linear")).next().expect("step 1's curve");
    curve.click();
    harness.run_steps(2);
    harness.get_by_label("Ease in-out").click();
    harness.run_steps(3);
    let easing =
        |harness: &Harness<'static, StudioApp>| harness.state().document.project.servo.actions[0].steps[0].easing;
    assert_eq!(easing(&harness), Easing::EaseInOut);
    // Derived in the frame in tests (common::ui's Costing): shown at once.
    let meter = harness.get_by_label_contains("On the board:");
    let text = egui_kittest::kittest::NodeT::accesskit_node(&meter).label().unwrap_or_default().to_string();
    assert!(text.contains("for curves") && text.contains(" of 262144 bytes"), "{text}");
    assert!(harness.query_by_label_contains("largest deviation from the curves 0.").is_some(), "within 1°");

    let events = harness.state().link.as_ref().unwrap().demo_board().unwrap().events().clone();
    harness.get_by_label("Play on board").click();
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut sent = Vec::new();
    while sent.last() != Some(&-90) {
        assert!(Instant::now() < deadline, "the curve never ended: {sent:?}");
        harness.step();
        common::ui::wait_for_news();
        while let Ok(event) = events.try_recv() {
            if let LinkEvent::Driver(SimEvent::Handled(Message::ExecuteActionRequest { moves })) = event {
                sent.extend(moves.iter().filter(|m| m.servo_id == 1).map(|m| m.degree));
            }
        }
    }
    assert!(sent.len() >= 3, "sub-steps, not one straight move: {sent:?}");
    assert!(sent.windows(2).all(|pair| pair[1] <= pair[0]), "{sent:?}");
    assert!(sent[0] > -20, "eased in: the first piece covers little of the way: {sent:?}");

    harness.state_mut().apply(Action::Undo);
    harness.run_steps(2);
    assert_eq!(easing(&harness), Easing::Linear, "one undo step");
}
