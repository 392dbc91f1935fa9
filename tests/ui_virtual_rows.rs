//! Every list and table of the editor lays out only the rows in view: with 500
//! items (255 servos, the most a board addresses), the rows laid out — counted
//! in the accessibility tree, where every widget drawn appears — stay within
//! what an 800-pixel window can show. These fail if a list stops being
//! virtualised.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_possible_truncation, clippy::cast_sign_loss)]

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{By, Queryable, by};
use servo_studio::device::{Direction, LogEntry};
use servo_studio::link::no_waker;
use servo_studio::project::plen2::{Frame, Motion, PlayEntry, PlayList, Plen2Project, Pose};
use servo_studio::project::{
    Action, Button, Command, Family, JoystickTable, Macro, Project, Run, Servo, ServoProject, Step,
};
use servo_studio::ui::{Action as UiAction, StudioApp, Tab};

const ITEMS: usize = 500;
const WINDOW_HEIGHT: f32 = 800.0;
/// Rows an 800-pixel window can show, were they only 16 pixels tall.
const VIEWPORT_ROWS: usize = (WINDOW_HEIGHT / 16.0) as usize;

fn harness(project: Project, tab: Tab, connect: bool) -> Harness<'static, StudioApp> {
    let data = tempfile::tempdir().unwrap().keep();
    let mut app = StudioApp::new(project, None, no_waker()).with_data_dir(data);
    if connect {
        app.apply(UiAction::ConnectDemo);
        assert!(app.link.is_some(), "{:?}", app.status);
    }
    app.apply(UiAction::ShowTab(tab));
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1200.0, WINDOW_HEIGHT))
        .with_context_setup(servo_studio::ui::fonts::install)
        .with_accessibility_check(false)
        .build_ui_state(|ui, app: &mut StudioApp| app.show(ui), app);
    harness.run_steps(3);
    harness
}

/// Widgets laid out that match `rows` (one per row), checked to be some (the
/// list is shown) and no more than a window's worth.
fn assert_rows_in_view(harness: &Harness<'static, StudioApp>, rows: By<'_>, what: &str) -> usize {
    let laid_out = harness.query_all(rows).count();
    assert!(laid_out >= 3, "{what}: only {laid_out} rows shown");
    assert!(laid_out <= VIEWPORT_ROWS, "{what}: {laid_out} of {ITEMS} rows laid out (a window shows {VIEWPORT_ROWS})");
    laid_out
}

fn servos(count: usize) -> Vec<Servo> {
    (0..count).map(|id| Servo::new(u8::try_from(id).unwrap(), format!("舵機{id}"))).collect()
}

#[test]
fn the_servo_sliders_and_settings_lay_out_the_rows_in_view() {
    let project = ServoProject { servos: servos(255), ..ServoProject::default() };
    let mut harness = harness(Project::servo(project), Tab::Servos, false);
    assert_rows_in_view(&harness, by().role(Role::Slider).label_contains("舵機"), "servo sliders");
    harness.get_by_label_contains("Servo settings").click();
    // Past the opening animation.
    harness.run_steps(30);
    // Each settings row ends with its remove button.
    assert_rows_in_view(&harness, by().role(Role::Button).label("×"), "servo settings");
}

#[test]
fn the_action_list_and_its_steps_lay_out_the_rows_in_view() {
    let steps: Vec<Step> = (0..255u8).map(|servo_id| Step { servo_id, degree: 0, interval_10ms: 50 }).collect();
    let actions = (1..=ITEMS)
        .map(|id| Action {
            id: i32::try_from(id).unwrap(),
            caption: format!("動作{id}"),
            steps: if id == 1 { steps.clone() } else { Vec::new() },
        })
        .collect();
    let project = ServoProject { servos: servos(255), actions, ..ServoProject::default() };
    let harness = harness(Project::servo(project), Tab::Actions, false);
    assert_rows_in_view(&harness, by().label_contains("動作"), "action list");
    // Each step row ends with its remove button.
    assert_rows_in_view(&harness, by().role(Role::Button).label("×"), "step table");
}

#[test]
fn the_macro_list_and_its_commands_lay_out_the_rows_in_view() {
    let macros = (1..=ITEMS)
        .map(|id| Macro {
            id: i32::try_from(id).unwrap(),
            caption: format!("巨集{id}"),
            commands: if id == 1 {
                (0..ITEMS).map(|_| Command::once(Run::Delay { delay_ms: 100 })).collect()
            } else {
                Vec::new()
            },
        })
        .collect();
    let project = ServoProject { macros, ..ServoProject::default() };
    let harness = harness(Project::servo(project), Tab::Macros, false);
    assert_rows_in_view(&harness, by().label_contains("巨集"), "macro list");
    // Each command row starts with its drag handle "≡ n".
    assert_rows_in_view(&harness, by().label_contains("≡ "), "command table");
}

#[test]
fn the_joystick_tables_and_buttons_lay_out_the_rows_in_view() {
    let buttons: Vec<Button> = (0..ITEMS)
        .map(|button| Button {
            id: 0x8000_0000 | u32::try_from(button).unwrap(),
            caption: format!("鍵{button}"),
            press_macro: None,
            long_press_macro: None,
            release_macro: None,
            uninterruptible: false,
        })
        .collect();
    let joystick_tables = (1..=ITEMS)
        .map(|id| JoystickTable {
            id: i32::try_from(id).unwrap(),
            caption: format!("表{id}"),
            buttons: if id == 1 { buttons.clone() } else { Vec::new() },
        })
        .collect();
    let project = ServoProject { joystick_tables, ..ServoProject::default() };
    let harness = harness(Project::servo(project), Tab::Joystick, false);
    assert_rows_in_view(&harness, by().label_contains("表"), "table list");
    // Each button row ends with its remove button.
    assert_rows_in_view(&harness, by().role(Role::Button).label("×"), "button table");
}

#[test]
fn the_packet_log_lays_out_the_rows_in_view() {
    let mut harness = harness(Project::servo(ServoProject::default()), Tab::Log, true);
    let log = &mut harness.state_mut().link.as_mut().unwrap().log;
    for index in 0..ITEMS {
        log.record(LogEntry {
            seconds: index as f64,
            direction: Direction::Received,
            name: "MarkerResponse".into(),
            fields: format!("entry {index}"),
            hex: "13 4c".into(),
        });
    }
    harness.run_steps(3);
    assert_rows_in_view(&harness, by().label_contains("MarkerResponse"), "packet log");
}

fn plen2(motions: usize, frames: usize, lists: usize, entries: usize) -> Project {
    let motions = (0..motions)
        .map(|index| Motion {
            slot: u8::try_from(index % 90).unwrap(),
            name: format!("Motion {index}"),
            frames: (0..frames).map(|_| Frame { transition_ms: 100, values_tenths_deg: Pose::default() }).collect(),
            loop_range: None,
            jump_slot: None,
        })
        .collect();
    let play_lists = (0..lists)
        .map(|index| PlayList {
            name: format!("清單{index}"),
            entries: (0..entries).map(|_| PlayEntry { slot: 0, plays: 1 }).collect(),
        })
        .collect();
    Project {
        family: Family::Plen2,
        plen2: Plen2Project { motions, play_lists, ..Default::default() },
        ..Project::default()
    }
}

#[test]
fn the_plen2_motion_list_and_frames_lay_out_the_rows_in_view() {
    let harness = harness(plen2(ITEMS, 2, 0, 0), Tab::Motions, false);
    assert_rows_in_view(&harness, by().label_contains("Motion "), "motion list");
    // A motion of 500 frames (more than the robot takes, still drawn): each row has a mirror button.
    let harness = crate::harness(plen2(1, ITEMS, 0, 0), Tab::Motions, false);
    assert_rows_in_view(&harness, by().role(Role::Button).label("Mirror L/R"), "frame table");
}

#[test]
fn the_plen2_play_lists_lay_out_the_rows_in_view() {
    let harness = harness(plen2(1, 1, ITEMS, ITEMS), Tab::PlayLists, false);
    assert_rows_in_view(&harness, by().label_contains("清單"), "play lists");
    // Each entry row ends with its remove button.
    assert_rows_in_view(&harness, by().role(Role::Button).label("×"), "play list entries");
}

#[test]
fn the_plen2_slot_map_lays_out_the_rows_in_view() {
    let data = tempfile::tempdir().unwrap().keep();
    let mut app = StudioApp::new(plen2(90, 1, 0, 0), None, no_waker()).with_data_dir(data);
    app.apply(UiAction::ShowTab(Tab::Board));
    // A short window: the 9 rows of 10 slots do not all fit.
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1200.0, 360.0))
        .with_context_setup(servo_studio::ui::fonts::install)
        .with_accessibility_check(false)
        .build_ui_state(|ui, app: &mut StudioApp| app.show(ui), app);
    harness.run_steps(3);
    let cells = harness.query_all_by_label_contains("Motion ").count();
    assert!(cells >= 10, "{cells} slots shown");
    assert!(cells < 90, "all 90 slots laid out in a window that shows {cells}");
    assert_eq!(cells % 10, 0, "whole rows of ten");
}

#[test]
fn a_drop_down_of_500_actions_lays_out_the_choices_in_view() {
    let actions: Vec<Action> = (1..=ITEMS)
        .map(|id| Action { id: i32::try_from(id).unwrap(), caption: format!("動作{id}"), steps: Vec::new() })
        .collect();
    let macros =
        vec![Macro { id: 1, caption: "巨集".into(), commands: vec![Command::once(Run::Action { action_id: 400 })] }];
    let project = ServoProject { actions, macros, ..ServoProject::default() };
    let mut harness = harness(Project::servo(project), Tab::Macros, false);
    // The command's target: the second combo box of its row (after its kind).
    let combos: Vec<_> = harness.query_all(by().role(Role::ComboBox).label("≡ 1")).collect();
    assert_eq!(combos.len(), 2, "kind and target");
    combos[1].click();
    harness.run_steps(3);
    let choices = harness.query_all(by().label_contains("動作")).count();
    assert!(choices >= 3, "the drop-down opened: {choices} choices");
    assert!(choices <= VIEWPORT_ROWS, "{choices} of {ITEMS} choices laid out");
    // It opens at the current choice, 400 of 500, and the first ones are not laid out.
    assert!(harness.query_by_label("400 動作400").is_some(), "the current choice is in view");
    assert!(harness.query_by_label("1 動作1").is_none());
    // Picking one sets the command's target.
    harness.get_by_label("401 動作401").click();
    harness.run_steps(2);
    let run = harness.state().document.project.servo.macros[0].commands[0].run;
    assert_eq!(run, Run::Action { action_id: 401 });
}
