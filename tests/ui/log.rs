//! The packet log tab, against the in-process emulated board.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::time::{Duration, Instant};

use egui_kittest::kittest::Queryable;
use servo_studio::project::ServoProject;
use servo_studio::ui::{Action, Tab};

#[test]
fn the_log_shows_decoded_frames_and_filters_them() {
    let mut app = common::ui::editor(ServoProject::default());
    app.apply(Action::ConnectDemo);
    app.apply(Action::ShowTab(Tab::Log));
    let mut harness = common::ui::window(app, (1300.0, 800.0));
    // The status queries on connecting and their answers fill the log.
    let deadline = Instant::now() + Duration::from_secs(10);
    while harness.state().link.as_ref().unwrap().log.len() < 8 {
        assert!(Instant::now() < deadline, "the log stayed empty");
        harness.step();
        common::ui::wait_for_news();
    }
    harness.run_steps(2);
    assert!(harness.query_all_by_label_contains("→ QueryProjectIDRequest").next().is_some());
    assert!(harness.query_all_by_label_contains("← QueryProjectIDResponse").next().is_some());
    assert!(harness.query_all_by_label_contains("13 4c 05 1d").next().is_some(), "hex is shown");
    // Fields read as words, not Rust Debug syntax.
    assert!(harness.query_all_by_label_contains("QueryRemainPowerResponse battery 87.0 %").next().is_some());
    assert!(harness.query_all_by_label_contains("permil:").next().is_none());
    harness.get_by_role_and_label(egui::accesskit::Role::TextInput, "Filter").focus();
    harness.run_steps(1);
    harness.get_by_role_and_label(egui::accesskit::Role::TextInput, "Filter").type_text("RemainPower");
    harness.run_steps(2);
    assert!(harness.query_all_by_label_contains("QueryProjectID").next().is_none(), "filtered out");
    assert!(harness.query_all_by_label_contains("QueryRemainPowerResponse").next().is_some());
}
