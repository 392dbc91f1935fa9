//! A gamepad on the Drive panel, read from a named pipe of input events the
//! test writes: it drives the emulated base only while the dead-man is held
//! and the window has the focus; losing the focus, leaving the tab, releasing
//! the dead-man and the pipe ending each stop it; after a halt the dead-man
//! must be pressed again.

#![cfg(unix)]
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::io::Write;
use std::path::PathBuf;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::gamepad::{ABS_Y, BTN_TL, PadState, RawEvent};
use servo_studio::project::{Family, Project};
use servo_studio::ui::{Action, Plen2BoardLink as _, RflexBoardLink as _, ServoBoardLink as _, StudioApp, Tab};

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
        harness.state_mut().apply(Action::UseGamepad(Some(fifo.clone())));
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
        common::ui::run_until(&mut self.harness, what, |app| {
            common::ui::rflex_ui(app).pad.state.as_ref().is_some_and(&read)
        });
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
    common::ui::run_until(&mut rig.harness, "the gamepad to be let go", |app| !app.desks.pad.in_use());
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

mod bindings {
    use super::*;
    use servo_studio::gamepad::{ABS_RX, BTN_SOUTH, BTN_WEST};
    use servo_studio::link::LinkEvent;
    use servo_studio::project::gamepad::{AxisBinding, AxisTarget, ButtonBinding, Fire, Mapping};
    use servo_studio::project::plen2::{Frame, Joint, Motion, Plen2Project, Pose};
    use servo_studio::protocol::plen2::Command;
    use servo_studio::sim::{Plen2SimCommand, Plen2SimEvent, Plen2State};

    /// A PLEN2 project whose gamepad moves the left shoulder with the right
    /// stick (asking for ±120°, beyond the joint's ±90°) and plays slot 3 on A.
    fn project() -> Project {
        let mut project = Project::empty(Family::Plen2);
        project.plen2 = Plen2Project {
            motions: vec![Motion {
                slot: 3,
                name: "Wave".into(),
                frames: vec![Frame::new(200, Pose::default())],
                loop_range: None,
                jump_slot: None,
            }],
            ..Plen2Project::default()
        };
        project.gamepad.plen2 = Mapping {
            axes: vec![AxisBinding::absolute(ABS_RX, AxisTarget::Joint(Joint::LeftShoulderPitch), (-120.0, 120.0))],
            buttons: vec![ButtonBinding { button: BTN_SOUTH, fire: Fire::Motion(3) }],
        };
        project
    }

    struct Robot {
        harness: Harness<'static, StudioApp>,
        pipe: std::fs::File,
        _folder: tempfile::TempDir,
    }

    impl Robot {
        fn start(tab: Tab) -> Self {
            let mut app = common::ui::editor(project());
            app.apply(Action::ConnectDemo);
            let mut harness = common::ui::showing(app, tab, (1200.0, 800.0));
            let folder = tempfile::tempdir().unwrap();
            let fifo: PathBuf = folder.path().join("pad");
            assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
            harness.state_mut().apply(Action::UseGamepad(Some(fifo.clone())));
            let pipe = std::fs::OpenOptions::new().write(true).open(&fifo).unwrap();
            harness.run_steps(2);
            Self { harness, pipe, _folder: folder }
        }

        fn frame(&mut self, events: &[RawEvent]) {
            let mut bytes: Vec<u8> = events.iter().flat_map(|event| event.to_bytes(0)).collect();
            bytes.extend(RawEvent::report().to_bytes(0));
            self.pipe.write_all(&bytes).unwrap();
        }

        fn robot(&self) -> Plen2State {
            let (reply, state) = crossbeam_channel::bounded(1);
            self.harness.state().link.as_ref().unwrap().demo_plen2().unwrap().command(Plen2SimCommand::Inspect(reply));
            state.recv_timeout(std::time::Duration::from_secs(10)).unwrap()
        }

        /// Runs frames until the robot executes a command `wanted` picks; whether it did (10 s
        /// tell a hang apart).
        fn executes(&mut self, wanted: impl Fn(&Command) -> bool) -> bool {
            self.executed_until(wanted).is_some()
        }

        /// Every command the robot executes, in order, up to the first that
        /// `wanted` picks (`None`: none came within 10 s).
        fn executed_until(&mut self, wanted: impl Fn(&Command) -> bool) -> Option<Vec<Command>> {
            let events = self.harness.state().link.as_ref().unwrap().demo_plen2().unwrap().events().clone();
            let deadline = std::time::Instant::now() + std::time::Duration::from_secs(10);
            let mut executed = Vec::new();
            while std::time::Instant::now() < deadline {
                self.harness.step();
                for event in events.try_iter() {
                    if let LinkEvent::Driver(Plen2SimEvent::Executed(command)) = event {
                        let done = wanted(&command);
                        executed.push(command);
                        if done {
                            return Some(executed);
                        }
                    }
                }
                // The robot answers on its own threads: wait for its next event, not a spin.
                let _ = events.recv_timeout(std::time::Duration::from_millis(20)).map(|event| {
                    if let LinkEvent::Driver(Plen2SimEvent::Executed(command)) = event {
                        executed.push(command);
                    }
                });
                if executed.last().is_some_and(&wanted) {
                    return Some(executed);
                }
            }
            None
        }
    }

    #[test]
    fn an_axis_moves_its_joint_within_its_limits_and_a_button_plays_a_motion_on_the_robot() {
        let mut robot = Robot::start(Tab::Gamepad);
        // Full right: 120° asked, the joint stops at its limit of 90.0°.
        robot.frame(&[RawEvent::abs(ABS_RX, 32767)]);
        assert!(robot.executes(|command| matches!(command, Command::SetAngle { device: 0, angle: 900 })));
        assert_eq!(robot.robot().angles[0], 900);
        // A quarter left: beyond the 10 % dead zone, (0.25 − 0.1) / 0.9 = 1/6 of the way to −120°: −20.0°.
        robot.frame(&[RawEvent::abs(ABS_RX, -8192)]);
        assert!(robot.executes(|command| matches!(command, Command::SetAngle { device: 0, angle: -200 })));
        // Only that joint moved.
        let angles = robot.robot().angles;
        let home = Pose::default();
        assert!(
            angles.iter().enumerate().filter(|(device, _)| *device != 0).all(|(device, angle)| {
                let joint = Joint::ALL.iter().find(|joint| usize::from(joint.device_id()) == device);
                joint.is_none_or(|joint| *angle == joint.factory_home_tenths_deg() + home.get(*joint))
            }),
            "{angles:?}"
        );

        robot.frame(&[RawEvent::key(BTN_SOUTH, true)]);
        assert!(robot.executes(|command| *command == Command::PlayMotion { slot: 3 }), "A plays slot 3");

        // Test mode: buttons light up, nothing fires.
        robot.frame(&[RawEvent::key(BTN_SOUTH, false)]);
        let seen = |pressed: bool| {
            move |app: &StudioApp| app.desks.pad.state.as_ref().is_some_and(|pad| pad.pressed(BTN_SOUTH) == pressed)
        };
        common::ui::run_until(&mut robot.harness, "the release seen", seen(false));
        robot.harness.state_mut().apply(Action::PadTestMode(true));
        robot.frame(&[RawEvent::key(BTN_SOUTH, true)]);
        common::ui::run_until(&mut robot.harness, "the press seen", seen(true));
        // Out of test mode, the axis moves the joint: that command goes out after
        // anything the press could have fired, so the robot runs it after too.
        robot.harness.state_mut().apply(Action::PadTestMode(false));
        robot.frame(&[RawEvent::abs(ABS_RX, 32767)]);
        let executed = robot
            .executed_until(|command| matches!(command, Command::SetAngle { device: 0, angle: 900 }))
            .expect("the axis moved the joint");
        assert!(
            !executed.contains(&Command::PlayMotion { slot: 3 }),
            "nothing fired in test mode, though the press was seen: {executed:?}"
        );
    }

    #[test]
    fn a_button_is_bound_by_pressing_it_and_the_binding_is_one_undo_step() {
        let mut robot = Robot::start(Tab::Gamepad);
        robot.harness.get_by_label("Bind a button: press it").click();
        robot.harness.run_steps(2);
        assert!(robot.harness.query_by_label("Waiting for the gamepad… (Cancel to stop)").is_some());
        robot.frame(&[RawEvent::key(BTN_WEST, true)]);
        common::ui::run_until(&mut robot.harness, "the binding", |app| {
            app.document.project.gamepad.plen2.buttons.iter().any(|binding| binding.button == BTN_WEST)
        });
        // Bound to the first thing a button can fire (STOP) until changed; pressing it while
        // binding fired nothing.
        let bound = robot.harness.state().document.project.gamepad.plen2.buttons.last().cloned().unwrap();
        assert_eq!(bound, ButtonBinding { button: BTN_WEST, fire: Fire::Stop });
        assert_eq!(
            robot.harness.query_all_by_label("BTN_WEST").count(),
            2,
            "lit in the test view, and its binding's row"
        );
        robot.harness.state_mut().apply(Action::Undo);
        assert_eq!(robot.harness.state().document.project.gamepad.plen2.buttons.len(), 1, "one undo step");

        // The same button bound twice is named as a conflict.
        robot.harness.state_mut().apply(Action::Redo);
        let mut mapping = robot.harness.state().document.project.gamepad.plen2.clone();
        mapping.buttons.push(ButtonBinding { button: BTN_WEST, fire: Fire::Motion(3) });
        robot.harness.state_mut().apply(Action::Edit {
            edit: servo_studio::project::Edit::SetGamepad(Family::Plen2, Box::new(mapping)),
            coalesce: None,
        });
        robot.harness.run_steps(2);
        assert!(robot.harness.query_by_label("Conflict: BTN_WEST is bound more than once").is_some());
    }
}

mod other_families {
    use super::*;
    use servo_studio::gamepad::{ABS_RX, BTN_EAST, BTN_SOUTH};
    use servo_studio::link::LinkEvent;
    use servo_studio::project::gamepad::{AxisBinding, AxisTarget, ButtonBinding, Fire, Mapping};
    use servo_studio::protocol::servo::Message;
    use servo_studio::sim::{RflexSimCommand, SimEvent};

    fn pad(harness: &mut Harness<'static, StudioApp>, folder: &tempfile::TempDir) -> std::fs::File {
        let fifo: PathBuf = folder.path().join("pad");
        assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
        harness.state_mut().apply(Action::UseGamepad(Some(fifo.clone())));
        let pipe = std::fs::OpenOptions::new().write(true).open(&fifo).unwrap();
        harness.run_steps(2);
        pipe
    }

    fn frame(pipe: &mut std::fs::File, events: &[RawEvent]) {
        let mut bytes: Vec<u8> = events.iter().flat_map(|event| event.to_bytes(0)).collect();
        bytes.extend(RawEvent::report().to_bytes(0));
        pipe.write_all(&bytes).unwrap();
    }

    /// A servo board: the right stick moves servo 1 within its limits, A runs macro 1 on the board.
    #[test]
    fn a_servo_axis_moves_its_servo_and_a_button_runs_a_macro_on_the_board() {
        let mut project = servo_studio::ui::sample_project();
        let servo = project.servo.servos[0].clone();
        let macro_id = project.servo.macros.first().map_or(1, |run| run.id);
        project.gamepad.servo = Mapping {
            axes: vec![AxisBinding::absolute(ABS_RX, AxisTarget::Servo(servo.id), (-180.0, 180.0))],
            buttons: vec![ButtonBinding { button: BTN_SOUTH, fire: Fire::Macro(macro_id) }],
        };
        let mut app = common::ui::editor(project);
        app.apply(Action::ConnectDemo);
        let mut harness = common::ui::showing(app, Tab::Gamepad, (1200.0, 800.0));
        let folder = tempfile::tempdir().unwrap();
        let mut pipe = pad(&mut harness, &folder);
        let events = harness.state().link.as_ref().unwrap().demo_board().unwrap().events().clone();
        let handled = |harness: &mut Harness<'static, StudioApp>, wanted: &dyn Fn(&Message) -> bool| {
            let deadline = std::time::Instant::now() + std::time::Duration::from_secs(10);
            while std::time::Instant::now() < deadline {
                harness.step();
                common::ui::wait_for_news();
                for event in events.try_iter() {
                    if let LinkEvent::Driver(SimEvent::Handled(message)) = event
                        && wanted(&message)
                    {
                        return true;
                    }
                }
            }
            false
        };
        // Full right asks for 180°: the servo stops at its own maximum.
        frame(&mut pipe, &[RawEvent::abs(ABS_RX, 32767)]);
        let top = servo.max_deg;
        assert!(handled(&mut harness, &|message| matches!(message,
            Message::ExecuteActionRequest { moves } if moves.iter().any(|m| m.servo_id == servo.id && m.degree == top))));
        frame(&mut pipe, &[RawEvent::key(BTN_SOUTH, true)]);
        assert!(handled(&mut harness, &|message| *message == Message::ExecuteMacroRequest { macro_id }));
    }

    /// An rFLEX base: B sets the brake.
    #[test]
    fn an_rflex_button_sets_the_brake() {
        let mut project = Project::empty(Family::Rflex);
        project.gamepad.rflex.buttons = vec![ButtonBinding { button: BTN_EAST, fire: Fire::Brake }];
        let mut app = common::ui::editor(project);
        app.apply(Action::ConnectDemo);
        let mut harness = common::ui::showing(app, Tab::Drive, (1100.0, 800.0));
        harness.get_by_label("Brake").click();
        harness.run_steps(2);
        let folder = tempfile::tempdir().unwrap();
        let mut pipe = pad(&mut harness, &folder);
        let braked = |harness: &Harness<'static, StudioApp>| {
            let (reply, state) = crossbeam_channel::bounded(1);
            harness.state().link.as_ref().unwrap().demo_base().unwrap().command(RflexSimCommand::Inspect(reply));
            state.recv_timeout(std::time::Duration::from_secs(10)).unwrap().braked
        };
        common::ui::run_until(&mut harness, "the brake released", |app| {
            app.link.as_ref().and_then(|link| link.rflex()).is_some_and(|base| base.telemetry.brake == Some(false))
        });
        assert!(!braked(&harness));
        frame(&mut pipe, &[RawEvent::key(BTN_EAST, true)]);
        common::ui::run_until(&mut harness, "the brake set", |app| {
            app.link.as_ref().and_then(|link| link.rflex()).is_some_and(|base| base.telemetry.brake == Some(true))
        });
        assert!(braked(&harness));
    }
}
