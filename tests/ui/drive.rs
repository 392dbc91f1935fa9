//! Driving the emulated rFLEX base from the editor: an arrow key held drives
//! it, letting go stops it within one frame, STOP stops it, and a lost link is
//! reported and leaves the pad silent.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::link::LinkEvent;
use servo_studio::project::{Family, Project};
use servo_studio::protocol::rflex::Command;
use servo_studio::sim::{BaseState, RflexSimCommand, RflexSimEvent};
use servo_studio::ui::{Action, RflexBoardLink as _, StudioApp, Tab};

fn harness() -> Harness<'static, StudioApp> {
    let mut app = common::ui::editor(Project::empty(Family::Rflex));
    app.apply(Action::ConnectDemo);
    assert!(app.link.as_ref().is_some_and(|link| link.rflex().is_some()), "{:?}", app.status);
    common::ui::showing(app, Tab::Drive, (1100.0, 700.0))
}

fn status(harness: &Harness<'static, StudioApp>) -> String {
    harness.state().status.as_ref().map(|line| line.text.clone()).unwrap_or_default()
}

fn inspect(harness: &Harness<'static, StudioApp>) -> BaseState {
    let (reply, state) = crossbeam_channel::bounded(1);
    harness.state().link.as_ref().unwrap().demo_base().unwrap().command(RflexSimCommand::Inspect(reply));
    state.recv_timeout(Duration::from_secs(10)).unwrap()
}

/// Waits (on the base's own events) until it receives a motion command matching `wanted`.
fn wait_for_motion(harness: &Harness<'static, StudioApp>, what: &str, wanted: impl Fn(u32, u8) -> bool) {
    let events = harness.state().link.as_ref().unwrap().demo_base().unwrap().events().clone();
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        match events.recv_deadline(deadline) {
            Ok(LinkEvent::Driver(RflexSimEvent::Received(Command::AxisSetDir {
                axis: 0, speed, direction, ..
            }))) if wanted(speed, direction) => {
                return;
            }
            Ok(_) => {}
            Err(_) => panic!("the base never got {what}"),
        }
    }
}

#[test]
fn an_arrow_key_drives_the_base_and_letting_go_stops_it_within_one_frame() {
    let mut harness = harness();
    assert!(status(&harness).contains("braked"), "{}", status(&harness));
    harness.get_by_label("Brake").click();
    harness.run_steps(2);
    let deadline = Instant::now() + Duration::from_secs(10);
    while inspect(&harness).braked {
        assert!(Instant::now() < deadline, "the brake was never released");
        harness.step();
        common::ui::wait_for_news();
    }
    // The status line no longer says what the connection said.
    assert_eq!(status(&harness), "Brake released: the base can drive");

    harness.key_down(egui::Key::ArrowUp);
    harness.step();
    assert_eq!(common::ui::rflex_ui(harness.state()).drive_asked(), (0.5, 0.0), "the top speed from the project");
    wait_for_motion(&harness, "a forward command", |speed, direction| speed == 51_500 && direction == 1);
    // While the key is held the driver keeps re-sending at 10 Hz; the base gets going.
    let base = harness.state().link.as_ref().unwrap().rflex().unwrap();
    assert_eq!(base.commanded, (0.5, 0.0));
    assert!(inspect(&harness).target_speed_m_per_s > 0.49);

    // Let go: the stop is issued in that very frame.
    harness.key_up(egui::Key::ArrowUp);
    harness.step();
    assert_eq!(common::ui::rflex_ui(harness.state()).drive_asked(), (0.0, 0.0));
    assert_eq!(harness.state().link.as_ref().unwrap().rflex().unwrap().commanded, (0.0, 0.0));
    wait_for_motion(&harness, "the stop", |speed, _| speed == 0);
    assert_eq!(inspect(&harness).target_speed_m_per_s, 0.0);

    // STOP stops a base that is driving.
    harness.key_down(egui::Key::ArrowDown);
    harness.step();
    wait_for_motion(&harness, "a backward command", |speed, direction| speed == 51_500 && direction == 0);
    harness.get_all_by_label_contains("STOP").next().unwrap().click();
    harness.step();
    wait_for_motion(&harness, "the STOP", |speed, _| speed == 0);
    assert_eq!(inspect(&harness).target_speed_m_per_s, 0.0);
    // The key still held asks to drive on: refused until Resume, and said.
    assert!(harness.state().stopped());
    assert!(status(&harness).contains("press Resume"), "{}", status(&harness));
    harness.key_up(egui::Key::ArrowDown);
    harness.step();
    assert_eq!(inspect(&harness).target_speed_m_per_s, 0.0, "never driven after STOP");
    harness.get_by_label("Resume").click();
    harness.step();
    assert!(!harness.state().stopped(), "{}", status(&harness));
    harness.key_down(egui::Key::ArrowDown);
    harness.step();
    wait_for_motion(&harness, "a backward command after Resume", |speed, direction| speed == 51_500 && direction == 0);
    harness.key_up(egui::Key::ArrowDown);
    harness.step();
}

#[test]
fn a_lost_link_is_reported_and_the_pad_stops_sending() {
    let mut harness = harness();
    harness.get_by_label("Brake").click();
    harness.key_down(egui::Key::ArrowLeft);
    harness.step();
    wait_for_motion(&harness, "the first command", |_, _| true);
    // The cable is pulled: the base closes the link.
    harness.state().link.as_ref().unwrap().demo_base().unwrap().command(RflexSimCommand::Disconnect);
    let deadline = Instant::now() + Duration::from_secs(10);
    while harness.state().link.is_some() {
        assert!(Instant::now() < deadline, "the lost link was never noticed");
        harness.step();
        common::ui::wait_for_news();
    }
    let status = harness.state().status.clone().unwrap();
    assert!(status.is_error && status.text.starts_with("The board link ended"), "{status:?}");
    // Still holding the key: nothing is asked for any more.
    harness.step();
    assert_eq!(common::ui::rflex_ui(harness.state()).drive_asked(), (0.0, 0.0));
    assert!(harness.query_all_by_label("Not connected").next().is_some(), "the panels say the base is gone");
    harness.key_up(egui::Key::ArrowLeft);
}

#[test]
fn losing_window_focus_while_driving_stops_the_base() {
    let mut harness = harness();
    harness.get_by_label("Brake").click();
    harness.key_down(egui::Key::ArrowUp);
    harness.step();
    wait_for_motion(&harness, "a forward command", |speed, _| speed > 0);
    // Another window takes the focus while the key is still held.
    harness.event(egui::Event::WindowFocused(false));
    // eframe goes on saying so in every frame's input until the focus is back.
    harness.input_mut().focused = false;
    harness.step();
    assert_eq!(common::ui::rflex_ui(harness.state()).drive_asked(), (0.0, 0.0));
    wait_for_motion(&harness, "the stop", |speed, _| speed == 0);
    // The pad says why the keys do nothing now.
    harness.step();
    let why = "The keys do nothing: the window does not have the keyboard focus. Click in the window first.";
    assert!(harness.query_by_label(why).is_some());
    harness.key_up(egui::Key::ArrowUp);
    harness.event(egui::Event::WindowFocused(true));
    harness.input_mut().focused = true;
    harness.run_steps(2);
    assert!(harness.query_by_label(why).is_none(), "gone with the focus back");
}

#[test]
fn a_signal_to_end_the_editor_drops_the_base_link_and_keeps_the_work() {
    let mut harness = harness();
    let (terminate, terminated) = crossbeam_channel::bounded(1);
    harness.state_mut().terminate_on(terminated);
    // Unsaved work: a changed drive setting.
    let mut settings = harness.state().document.project.rflex.drive;
    settings.max_speed_m_per_s = 0.3;
    harness
        .state_mut()
        .apply(Action::Edit { edit: servo_studio::project::Edit::SetRflexDrive(settings), coalesce: None });
    harness.key_down(egui::Key::ArrowUp);
    harness.step();
    assert_eq!(common::ui::rflex_ui(harness.state()).drive_asked(), (0.3, 0.0));
    terminate.send(()).unwrap();
    harness.step();
    // Dropping the link is what stops and brakes a base (tested with the handle itself).
    assert!(harness.state().link.is_none(), "the base's link is closed: it was told to stop and brake");
    let recovery = harness.state().files.data_dir.join("recovery.json");
    let kept = servo_studio::ui::files::read_recovery(&harness.state().files.data_dir).expect("the work is kept");
    assert!(recovery.exists());
    assert_eq!(kept.project.rflex.drive.max_speed_m_per_s, 0.3);
    harness.key_up(egui::Key::ArrowUp);
}

/// The base's view beside its panels is its world, and says so on the tab row.
#[test]
fn the_tab_row_offers_the_world_view_not_a_3d_preview() {
    let harness = harness();
    assert!(harness.query_by_label("3D view").is_none(), "a base has no 3D preview");
    // The checkbox on the tab row, besides the view's own heading.
    assert!(harness.query_all_by_label("World view").count() >= 2);
}
