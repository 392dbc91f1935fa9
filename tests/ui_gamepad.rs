//! A gamepad on the Drive panel, read from a named pipe of input events the
//! test writes: it drives the emulated base only while the dead-man is held
//! and the window has the focus; losing the focus, leaving the tab, releasing
//! the dead-man and the pipe ending each stop it; after a halt the dead-man
//! must be pressed again.

#![cfg(unix)]
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::io::Write;
use std::path::PathBuf;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::gamepad::{ABS_Y, BTN_TL, PadState, RawEvent};
use servo_studio::project::{Family, Project};
use servo_studio::ui::{Action, RflexAction, StudioApp, Tab};

struct Rig {
    harness: Harness<'static, StudioApp>,
    pipe: Option<std::fs::File>,
    _folder: tempfile::TempDir,
}

impl Rig {
    /// The demo base, its brake released, and a gamepad on a named pipe.
    fn start() -> Self {
        let mut app = common::ui::editor(Project::empty(Family::Rflex));
        app.apply(Action::ConnectDemo);
        let mut harness = common::ui::showing(app, Tab::Drive, (1100.0, 800.0));
        harness.get_by_label("Brake").click();
        harness.run_steps(2);
        let folder = tempfile::tempdir().unwrap();
        let fifo: PathBuf = folder.path().join("pad");
        assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
        harness.state_mut().apply(Action::Rflex(RflexAction::UseGamepad(Some(fifo.clone()))));
        // Opening for writing waits for the reading thread to open it.
        let pipe = std::fs::OpenOptions::new().write(true).open(&fifo).unwrap();
        Self { harness, pipe: Some(pipe), _folder: folder }
    }

    fn frame(&mut self, events: &[RawEvent]) {
        let mut bytes: Vec<u8> = events.iter().flat_map(|event| event.to_bytes(0)).collect();
        bytes.extend(RawEvent::report().to_bytes(0));
        self.pipe.as_mut().unwrap().write_all(&bytes).unwrap();
    }

    fn commanded(app: &StudioApp) -> (f64, f64) {
        app.link.as_ref().and_then(|link| link.rflex()).map_or((0.0, 0.0), |base| base.commanded)
    }

    fn until(&mut self, what: &str, done: impl Fn((f64, f64)) -> bool) {
        common::ui::run_until(&mut self.harness, what, |app| done(Self::commanded(app)));
    }

    /// Once the window has read the pad into the state `read` describes, the base is still not driven.
    fn stays_stopped(&mut self, what: &str, read: impl Fn(&PadState) -> bool) {
        common::ui::run_until(&mut self.harness, what, |app| app.rflex.pad.state.as_ref().is_some_and(&read));
        self.harness.run_steps(2);
        assert_eq!(Self::commanded(self.harness.state()), (0.0, 0.0), "{what}");
    }
}

fn forward() -> [RawEvent; 2] {
    [RawEvent::key(BTN_TL, true), RawEvent::abs(ABS_Y, -32768)]
}

#[test]
fn the_gamepad_drives_while_the_dead_man_is_held_and_the_window_has_the_focus() {
    let mut rig = Rig::start();
    rig.frame(&[RawEvent::abs(ABS_Y, -32768)]);
    rig.stays_stopped("the stick alone drives nothing", |pad| pad.axis(ABS_Y) == -1.0);
    rig.frame(&forward());
    // The project's top speed (0.5 m/s) at full stick.
    rig.until("the pad to drive", |(speed, _)| (speed - 0.5).abs() < 1e-9);
    assert!(rig.harness.query_by_label_contains("— driving").is_some());
    rig.frame(&[RawEvent::key(BTN_TL, false)]);
    rig.until("the release to stop", |commanded| commanded == (0.0, 0.0));

    // Another window takes the focus: stopped, and not driven again until the dead-man is pressed anew.
    rig.frame(&forward());
    rig.until("the pad to drive", |(speed, _)| speed > 0.0);
    rig.harness.event(egui::Event::WindowFocused(false));
    rig.harness.input_mut().focused = false;
    rig.until("the lost focus to stop", |commanded| commanded == (0.0, 0.0));
    rig.harness.input_mut().focused = true;
    rig.harness.run_steps(2);
    rig.frame(&forward());
    rig.stays_stopped("held from before the halt", |pad| pad.pressed(BTN_TL));
    rig.frame(&[RawEvent::key(BTN_TL, false)]);
    rig.frame(&forward());
    rig.until("a fresh press to drive", |(speed, _)| speed > 0.0);

    // Leaving the Drive tab is letting go.
    rig.harness.state_mut().apply(Action::ShowTab(Tab::Telemetry));
    rig.until("leaving the tab to stop", |commanded| commanded == (0.0, 0.0));
    rig.harness.state_mut().apply(Action::ShowTab(Tab::Drive));
    rig.harness.run_steps(2);
    rig.frame(&[RawEvent::key(BTN_TL, false)]);
    rig.frame(&forward());
    rig.until("a fresh press to drive", |(speed, _)| speed > 0.0);

    // The pipe ends: stopped, and said.
    rig.pipe = None;
    rig.until("the end to stop", |commanded| commanded == (0.0, 0.0));
    common::ui::run_until(&mut rig.harness, "the gamepad to be let go", |app| !app.rflex.pad.in_use());
    let status = rig.harness.state().status.clone().unwrap();
    assert!(status.is_error && status.text.starts_with("The gamepad is gone"), "{status:?}");
}

#[test]
fn stop_halts_the_gamepad_until_its_dead_man_is_pressed_again() {
    let mut rig = Rig::start();
    rig.frame(&forward());
    rig.until("the pad to drive", |(speed, _)| speed > 0.0);
    rig.harness.state_mut().apply(Action::Stop);
    assert_eq!(Rig::commanded(rig.harness.state()), (0.0, 0.0));
    rig.frame(&[RawEvent::abs(ABS_Y, -30000)]);
    rig.stays_stopped("the stick moved, the dead-man still held from before STOP", |pad| pad.axis(ABS_Y) > -1.0);
    rig.frame(&[RawEvent::key(BTN_TL, false)]);
    rig.frame(&forward());
    rig.until("a fresh press to drive", |(speed, _)| speed > 0.0);
}
