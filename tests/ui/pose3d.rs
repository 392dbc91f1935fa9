//! Posing by touching the robot in its 3D view, as a user does it: hovering a
//! link names its joint and angle, a click selects it (its slider too, which
//! then takes the arrow keys, and the other way round), and a drag turns that
//! joint alone, clamped to its limits, sent to the robot, undone in one step.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::time::{Duration, Instant};

use egui::Pos2;
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable, by};
use servo_studio::link::LinkEvent;
use servo_studio::project::plen2::{Joint, JointSetting, Plen2Project};
use servo_studio::project::{self, Family, Project};
use servo_studio::protocol::plen2::Command;
use servo_studio::protocol::servo::Message;
use servo_studio::sim::{Plen2SimEvent, SimEvent};
use servo_studio::ui::{Action, Plen2BoardLink as _, ServoBoardLink as _, StudioApp, Tab};

/// Presses at `from`, moves the pointer `by` in a few frames, lets go.
fn drag(harness: &mut Harness<'static, StudioApp>, from: Pos2, by: egui::Vec2) {
    harness.drag_at(from);
    harness.step();
    for part in 1..=4u8 {
        harness.hover_at(from + by * f32::from(part) / 4.0);
        harness.step();
    }
    harness.drop_at(from + by);
    harness.run_steps(2);
}

fn undo(harness: &mut Harness<'static, StudioApp>) {
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run_steps(2);
}

const ROLL: Joint = Joint::LeftShoulderRoll;

fn plen2_harness() -> (Harness<'static, StudioApp>, (i16, i16)) {
    let home = ROLL.factory_home_tenths_deg();
    let (low, high) = (home - 150, home + 200);
    let setting = JointSetting { joint: ROLL, min_tenths_deg: low, max_tenths_deg: high, home_tenths_deg: home };
    let project = Project {
        family: Family::Plen2,
        plen2: Plen2Project { joints: vec![setting], ..Default::default() },
        ..Project::default()
    };
    let mut app = common::ui::editor(project);
    app.apply(Action::ConnectDemo);
    (common::ui::showing(app, Tab::Joints, (1200.0, 800.0)), (low, high))
}

fn grip(harness: &Harness<'static, StudioApp>) -> Pos2 {
    common::ui::plen2_ui(harness.state()).preview.joint_on_screen(ROLL).expect("the shoulder is drawn")
}

/// Runs frames until the robot has executed `$AN` putting the joint at `angle`.
fn robot_reaches(harness: &mut Harness<'static, StudioApp>, angle: i16) {
    let events = harness.state().link.as_ref().unwrap().demo_plen2().unwrap().events().clone();
    let device = ROLL.device_id();
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        assert!(Instant::now() < deadline, "the robot never turned the shoulder to {angle}");
        harness.step();
        common::ui::wait_for_news();
        while let Ok(event) = events.try_recv() {
            if let LinkEvent::Driver(Plen2SimEvent::Executed(Command::SetAngle { device: d, angle: a })) = event
                && d == device
                && a == angle
            {
                return;
            }
        }
    }
}

#[test]
fn a_plen2_joint_is_named_selected_and_turned_by_touching_it_clamped_and_undone_in_one_step() {
    let (mut harness, (low, high)) = plen2_harness();
    let home = common::ui::plen2_ui(harness.state()).pose;
    let at = grip(&harness);
    harness.hover_at(at);
    harness.run_steps(8);
    let name = format!("left_shoulder_roll #{}  {:.1}°", ROLL.device_id(), f64::from(home[ROLL.index()]) / 10.0);
    // Said in a tooltip at the pointer, once it rests there.
    assert!(harness.query_by_label_contains(&name).is_some(), "hovering names the joint and its angle: {name}");

    // A click selects the joint; its slider takes the arrow keys.
    harness.drag_at(at);
    harness.step();
    harness.drop_at(at);
    harness.run_steps(3);
    assert_eq!(common::ui::plen2_ui(harness.state()).selected_joint, Some(ROLL));
    harness.key_press(egui::Key::ArrowRight);
    harness.run_steps(2);
    assert_eq!(
        common::ui::plen2_ui(harness.state()).pose[ROLL.index()],
        home[ROLL.index()] + 10,
        "the selected slider has the keys"
    );
    let before = common::ui::plen2_ui(harness.state()).pose;
    assert!(!harness.state().document.can_undo(), "slider moves are live, not edits");

    // A long drag one way: that joint alone turns, as far as its limit.
    let at = grip(&harness);
    drag(&mut harness, at, egui::vec2(320.0, 0.0));
    let first = common::ui::plen2_ui(harness.state()).pose;
    let end = first[ROLL.index()];
    assert!(end == low || end == high, "clamped to a limit ({low}, {high}): {end}");
    for joint in Joint::ALL.into_iter().filter(|&joint| joint != ROLL) {
        assert_eq!(first[joint.index()], before[joint.index()], "{joint:?} did not move");
    }
    robot_reaches(&mut harness, end);

    // One undo step brings the whole drag back, to the robot too.
    undo(&mut harness);
    assert_eq!(common::ui::plen2_ui(harness.state()).pose, before);
    assert!(!harness.state().document.can_undo(), "the drag was one step");
    robot_reaches(&mut harness, before[ROLL.index()]);
    // Redo turns it again.
    harness.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::Z);
    harness.run_steps(2);
    assert_eq!(common::ui::plen2_ui(harness.state()).pose, first);
    undo(&mut harness);

    // The other way: the other limit.
    let at = grip(&harness);
    drag(&mut harness, at, egui::vec2(-320.0, 0.0));
    let other = common::ui::plen2_ui(harness.state()).pose[ROLL.index()];
    assert_eq!([end.min(other), end.max(other)], [low, high], "each way reaches its own limit");

    // The other way round: a slider's name selects its joint in the view.
    let knee = format!("left_knee_pitch #{}", Joint::LeftKneePitch.device_id());
    let name = harness
        .query_all(by().label_contains(&knee).include_labels())
        .find(|node| node.accesskit_node().role() == Role::Button);
    name.expect("the knee's name").click();
    harness.run_steps(2);
    assert_eq!(common::ui::plen2_ui(harness.state()).selected_joint, Some(Joint::LeftKneePitch));
}

#[test]
fn a_turn_in_the_3d_view_is_recorded_like_a_slider() {
    let mut project = Project { family: Family::Plen2, ..Project::default() };
    project.plen2.motions.push(project::plen2::Motion {
        slot: 5,
        name: "Touched".into(),
        frames: Vec::new(),
        loop_range: None,
        jump_slot: None,
    });
    let mut harness = common::ui::showing(common::ui::editor(project), Tab::Joints, (1200.0, 800.0));
    let home = common::ui::plen2_ui(harness.state()).pose[ROLL.index()];
    common::ui::record_through_count_in(&mut harness);
    let at = grip(&harness);
    drag(&mut harness, at, egui::vec2(120.0, 0.0));
    harness.run_steps(4);
    let turned = common::ui::plen2_ui(harness.state()).pose[ROLL.index()];
    assert_ne!(turned, home);
    harness.get_by_label("■ Stop recording").click();
    harness.run_steps(2);
    let motion = &harness.state().document.project.plen2.motions[0];
    let last = motion.frames.last().expect("the recording became frames");
    assert!((last.values_tenths_deg.get(ROLL) - (turned - home)).abs() <= 10, "{motion:?}");
}

const ELBOW_ROLL: u8 = 2;

#[test]
fn a_servo_of_the_rig_is_turned_by_touching_it_clamped_and_undone_in_one_step() {
    let mut servo = common::sample_biped();
    let shoulder = servo.servos.iter_mut().find(|s| s.id == ELBOW_ROLL).unwrap();
    (shoulder.min_deg, shoulder.max_deg) = (-20, 35);
    let mut app = common::ui::editor(servo);
    app.apply(Action::ConnectDemo);
    let mut harness = common::ui::showing(app, Tab::Servos, (1200.0, 800.0));
    let before = common::ui::servo_ui(harness.state()).pose.clone();
    let at = common::ui::servo_ui(harness.state()).figure.servo_on_screen(ELBOW_ROLL).expect("the shoulder is drawn");
    harness.hover_at(at);
    harness.run_steps(8);
    assert!(harness.query_by_label_contains("L shoulder roll 左肩側擺 #2  0°").is_some(), "hovering names it");
    drag(&mut harness, at, egui::vec2(300.0, 0.0));
    let after = common::ui::servo_ui(harness.state()).pose.clone();
    let end = after[&ELBOW_ROLL];
    assert!(end == -20 || end == 35, "clamped to a limit: {end}");
    assert_eq!(common::ui::servo_ui(harness.state()).selected_servo, Some(ELBOW_ROLL));
    for (id, degree) in &before {
        if *id != ELBOW_ROLL {
            assert_eq!(after[id], *degree, "servo {id} did not move");
        }
    }
    // Sent to the board.
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let link = harness.state().link.as_ref().unwrap();
        let event = link.demo_board().unwrap().events().recv_deadline(deadline).expect("the move arrived in time");
        if let LinkEvent::Driver(SimEvent::Handled(Message::ExecuteActionRequest { moves })) = event
            && moves.iter().any(|m| m.servo_id == ELBOW_ROLL && m.degree == end)
        {
            break;
        }
    }
    undo(&mut harness);
    assert_eq!(common::ui::servo_ui(harness.state()).pose, before);
    assert!(!harness.state().document.can_undo(), "the drag was one step");
}
