//! The graph pane: keys dragged in time and value, handles that shape a
//! move, a box that selects keys across channels, each drag one undo step;
//! the legend that shows, hides and solos channels.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::path::Path;

use egui::{Pos2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable, by};
use servo_studio::device::plen2::stored_motion;
use servo_studio::project::plen2::{Frame, Joint, Motion, Plen2Project, Pose};
use servo_studio::project::{Easing, Family, Project};
use servo_studio::protocol::plen2::playback::cycles_for;
use servo_studio::ui::{Action, StudioApp, Tab};

fn plen2() -> Project {
    let mut pose = Pose::default();
    pose.set(Joint::LeftShoulderPitch, 300);
    pose.set(Joint::LeftThighYaw, -200);
    let mut last = pose;
    last.set(Joint::LeftThighYaw, 200);
    let motion = Motion {
        slot: 3,
        name: "Wave".into(),
        frames: vec![Frame::new(320, pose), Frame::new(640, Pose::default()), Frame::new(320, last)],
        loop_range: None,
        jump_slot: None,
    };
    Project {
        family: Family::Plen2,
        plen2: Plen2Project { motions: vec![motion], ..Default::default() },
        ..Project::default()
    }
}

fn harness(project: Project, tab: Tab) -> Harness<'static, StudioApp> {
    common::ui::showing(common::ui::editor(project), tab, (1280.0, 1000.0))
}

fn motion(harness: &Harness<'static, StudioApp>) -> Motion {
    harness.state().document.project.plen2.motions[0].clone()
}

fn center(harness: &Harness<'static, StudioApp>, label: &str) -> Pos2 {
    harness.get_by_label(label).rect().center()
}

/// A press at `from`, the pointer moved by `by` in a few steps, released.
fn drag(harness: &mut Harness<'static, StudioApp>, from: Pos2, by: egui::Vec2) {
    harness.drag_at(from);
    harness.run();
    for step in 1..=4 {
        #[allow(clippy::cast_precision_loss)]
        harness.hover_at(from + by * (step as f32 / 4.0));
        harness.run();
    }
    harness.drop_at(from + by);
    harness.run();
}

#[test]
fn dragging_a_key_retimes_its_frame_by_whole_cycles_and_is_one_undo_step() {
    let mut harness = harness(plen2(), Tab::Motions);
    let before = motion(&harness);
    let key = center(&harness, "key left_shoulder_pitch #0");
    drag(&mut harness, key, vec2(60.0, 0.0));
    let after = motion(&harness);
    let cycles: Vec<u8> = after.frames.iter().map(|frame| cycles_for(frame.transition_ms)).collect();
    assert!(cycles[0] > 10, "later: {cycles:?}");
    assert_eq!(cycles[0] + cycles[1], 30, "the next frame gives up the time: later keys stay ({cycles:?})");
    assert_eq!(after.frames[0].transition_ms % 32, 0, "whole cycles");
    assert_eq!(after.frames[2], before.frames[2]);
    assert_eq!(after.frames[0].values_tenths_deg, before.frames[0].values_tenths_deg, "moved in time only");
    // The key follows, on the graph too.
    let moved = center(&harness, "key left_shoulder_pitch #0");
    assert!((moved.x - key.x - 60.0).abs() < 12.0, "{key:?} → {moved:?}");
    harness.state_mut().apply(Action::Undo);
    harness.run();
    assert_eq!(motion(&harness), before, "one undo step undoes the whole drag");
}

#[test]
fn dragging_a_key_up_changes_its_value_within_the_joints_limits() {
    let mut harness = harness(plen2(), Tab::Motions);
    let key = center(&harness, "key left_shoulder_pitch #0");
    drag(&mut harness, key, vec2(0.0, -40.0));
    let value = motion(&harness).frames[0].values_tenths_deg.get(Joint::LeftShoulderPitch);
    assert!(value > 300, "up: {value}");
    assert_eq!(motion(&harness).frames[0].transition_ms, 320, "in value only");
    // Far past the top: stopped at the limit (the factory's ±90° around home; frames are relative to home).
    let key = center(&harness, "key left_shoulder_pitch #0");
    drag(&mut harness, key, vec2(0.0, -5000.0));
    let value = motion(&harness).frames[0].values_tenths_deg.get(Joint::LeftShoulderPitch);
    assert_eq!(value, 900 - Joint::LeftShoulderPitch.factory_home_tenths_deg(), "stopped at the limit");
    // The lowest key dragged up: the view holds still under the pointer (it fitted the curves).
    let key = center(&harness, "key left_thigh_yaw #0");
    drag(&mut harness, key, vec2(0.0, -60.0));
    let value = motion(&harness).frames[0].values_tenths_deg.get(Joint::LeftThighYaw);
    assert!(value > -200, "up: {value}");
    let moved = center(&harness, "key left_thigh_yaw #0");
    assert!((moved.y - (key.y - 60.0)).abs() < 30.0, "{key:?} → {moved:?}");
}

#[test]
fn a_handle_drag_shapes_the_move_changes_what_the_robot_stores_and_the_meter() {
    let mut harness = harness(plen2(), Tab::Motions);
    assert!(harness.query_by_label_contains("On the robot").is_none(), "no curve, no meter");
    // (Key #2: at #1 every joint is at 0, one key over another.)
    harness.get_by_label("key left_shoulder_pitch #2").click();
    harness.run();
    let handle = center(&harness, "handle out left_shoulder_pitch #2");
    drag(&mut harness, handle, vec2(-15.0, 30.0));
    let shaped = motion(&harness);
    let Easing::Shaped(handles) = shaped.frames[2].easing else { panic!("{:?}", shaped.frames[2].easing) };
    assert!(handles.out[0] < 333, "the handle went earlier: {handles:?}");
    assert_eq!(shaped.frames[1].easing, Easing::Linear);
    let stored = stored_motion(&shaped);
    assert!(stored.frames.len() > 3, "the curve is stored as more straight frames: {}", stored.frames.len());
    let meter = harness.get_by_label_contains("On the robot").accesskit_node().label().unwrap_or_default();
    assert!(meter.contains(&format!("On the robot: {} frames of 20", stored.frames.len())), "{meter}");
    // What the robot plays is drawn against the curve.
    assert!(harness.query_all(by().value("dashed: what the board plays")).next().is_some());
    harness.state_mut().apply(Action::Undo);
    harness.run();
    assert_eq!(motion(&harness).frames[2].easing, Easing::Linear, "one undo step");
    assert!(harness.query_by_label_contains("On the robot").is_none());
}

#[test]
fn a_box_selects_keys_across_channels_and_they_move_together_pasting_a_curve_shapes_them_all() {
    let mut harness = harness(plen2(), Tab::Motions);
    let a = center(&harness, "key left_shoulder_pitch #2");
    let b = center(&harness, "key left_thigh_yaw #2");
    let (low, high) = (a.y.min(b.y), a.y.max(b.y));
    // Shift+drag around the last keys of both channels.
    harness.event(egui::Event::ModifiersChanged(egui::Modifiers::SHIFT));
    let corner = Pos2::new(a.x - 15.0, low - 8.0);
    drag(&mut harness, corner, vec2(30.0, high - low + 16.0));
    harness.event(egui::Event::ModifiersChanged(egui::Modifiers::NONE));
    harness.run();
    assert!(harness.query_all(by().value("2 keys selected")).next().is_some(), "the two keys in the box, none at 0°");
    let before = motion(&harness);
    drag(&mut harness, a, vec2(0.0, -20.0));
    let after = motion(&harness);
    let up =
        |joint: Joint| after.frames[2].values_tenths_deg.get(joint) - before.frames[2].values_tenths_deg.get(joint);
    assert!(up(Joint::LeftShoulderPitch) > 0, "moved up");
    assert_eq!(up(Joint::LeftShoulderPitch), up(Joint::LeftThighYaw), "together, by as much");
    assert_eq!(after.frames[1], before.frames[1]);
    // Shape frame #2's move by a handle, copy that curve, paste it on frame #0's.
    harness.get_by_label("key left_shoulder_pitch #2").click();
    harness.run();
    let handle = center(&harness, "handle in left_shoulder_pitch #2");
    drag(&mut harness, handle, vec2(25.0, 0.0));
    let shaped = motion(&harness).frames[2].easing;
    assert!(matches!(shaped, Easing::Shaped(_)), "{shaped:?}");
    harness.get_by_label("Copy curve").click();
    harness.run();
    harness.get_by_label("key left_thigh_yaw #0").click();
    harness.run();
    harness.get_by_label("Paste curve").click();
    harness.run();
    assert_eq!(motion(&harness).frames[0].easing, shaped, "pasted");
    harness.state_mut().apply(Action::Undo);
    harness.run();
    assert_eq!(motion(&harness).frames[0].easing, Easing::Linear, "one undo step");
}

#[test]
fn the_legend_shows_every_name_whole_hides_and_solos_channels() {
    let mut harness = harness(plen2(), Tab::Motions);
    // Every joint is listed; the first eight drawn (their keys can be grabbed).
    // Every joint is listed (the list scrolls: the rows in view are laid out); the first eight drawn.
    for (index, joint) in Joint::ALL.into_iter().enumerate().take(10) {
        let entry = format!("{} {}", if index < 8 { "●" } else { "○" }, joint.name());
        assert!(harness.query_by_label(&entry).is_some(), "{entry}");
    }
    assert!(harness.query_by_label("key left_foot_roll #0").is_none(), "not drawn at first");
    harness.get_by_label("○ left_foot_roll").click();
    harness.run();
    assert!(harness.query_by_label("key left_foot_roll #0").is_some(), "shown on a click");
    // Solo: that channel alone.
    assert!(harness.query_all_by_label("Solo").count() >= 8);
    harness.query_all_by_label("Solo").nth(1).unwrap().click();
    harness.run();
    assert!(harness.query_by_label("key left_thigh_yaw #0").is_some());
    assert!(harness.query_by_label("key left_shoulder_pitch #0").is_none(), "the others hidden");
    // The name is never cut: the legend is as wide as its widest name, left of the curves.
    harness.query_all_by_label("Solo").nth(1).unwrap().click();
    harness.run();
    let name = harness.get_by_label("○ right_shoulder_pitch").rect();
    let first_key = center(&harness, "key left_shoulder_pitch #0");
    assert!(name.width() > 100.0 && name.right() < first_key.x - 20.0, "{name:?} vs {first_key:?}");
}

#[test]
fn a_servo_steps_key_dragged_retimes_the_step_by_whole_updates_one_undo_step() {
    let project =
        servo_studio::project::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/project-v1.json"))
            .unwrap();
    let mut harness = harness(project, Tab::Actions);
    let before = harness.state().document.project.servo.actions[0].clone();
    let label = harness.get_by_label_contains("key 1 ").accesskit_node().label().unwrap_or_default();
    let key = center(&harness, &label);
    drag(&mut harness, key, vec2(40.0, 0.0));
    let after = harness.state().document.project.servo.actions[0].clone();
    assert!(after.steps[0].interval_10ms > before.steps[0].interval_10ms, "{:?}", after.steps[0]);
    assert_eq!(after.steps[0].degree, before.steps[0].degree);
    assert_eq!(after.steps[1], before.steps[1]);
    harness.state_mut().apply(Action::Undo);
    harness.run();
    assert_eq!(harness.state().document.project.servo.actions[0], before);
}
