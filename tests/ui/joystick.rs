//! The joystick mapping panel (`src/ui/servo/joystick.rs`), through egui_kittest.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::protocol::servo::ButtonEvent;
use servo_studio::sim::SimCommand;
use servo_studio::ui::{Action, ServoBoardLink as _, StudioApp, Tab};

use super::macros::{fixture, harness};
use common::ui::run_until;

#[test]
fn a_button_pressed_on_the_remote_is_picked_or_added() {
    let mut harness = harness(fixture(), Tab::Joystick);
    harness.state_mut().apply(Action::ConnectDemo);
    harness.run_steps(2);
    harness.get_by_label("Press a button to pick it").click();
    harness.run_steps(2);
    assert!(common::ui::servo_ui(harness.state()).picking.is_some());
    // The subscription must reach the board before the press; wait for the board to have handled it.
    let press = |harness: &Harness<'static, StudioApp>, button_id| {
        let link = harness.state().link.as_ref().unwrap();
        link.demo_board().unwrap().command(SimCommand::Button { button_id, event: ButtonEvent::Press });
    };
    run_until(&mut harness, "the subscription", |app| {
        common::ui::servo_board(app)
            .unwrap()
            .requester()
            .request(servo_studio::protocol::servo::Message::QueryProjectIdRequest)
            .is_ok()
    });
    press(&harness, 0x8000_0001);
    run_until(&mut harness, "the picked button", |app| common::ui::servo_ui(app).picked_button == Some(0x8000_0001));
    harness.run_steps(2);
    assert_eq!(
        harness.state().document.project.servo.joystick_tables[0].buttons.len(),
        2,
        "an existing button is selected, not added"
    );
    assert!(harness.query_all_by_label_contains("→ 0x80000001").next().is_some());
    assert!(harness.query_by_label_contains("0x80000001 press").is_some(), "shown among the live events");

    // A button the table does not have yet is added.
    harness.get_by_label("Press a button to pick it").click();
    harness.run_steps(2);
    press(&harness, 0x0000_0042);
    run_until(&mut harness, "the new button", |app| common::ui::servo_ui(app).picked_button == Some(0x42));
    let buttons = &harness.state().document.project.servo.joystick_tables[0].buttons;
    assert_eq!(buttons.len(), 3);
    assert_eq!(buttons[2].id, 0x42);
}
