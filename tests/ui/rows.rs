//! Every list and table of the editor fills the height it is given and lays
//! out only the rows in view: with 500 items (255 servos, the most a board
//! addresses) the rows laid out — counted in the accessibility tree, where
//! every widget drawn appears — are at least as many as fit between the
//! list's top and what is under it, and at most three more (the row cut by the
//! edge, and the two egui lays out past it), in a 1600 × 1000 and an 1100 ×
//! 720 window. These fail if a list is capped again or stops being
//! virtualised.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_possible_truncation, clippy::cast_sign_loss)]

use crate::common;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{By, Queryable, by};
use servo_studio::device::{Direction, LogEntry};
use servo_studio::project::plen2::{Frame, Motion, PlayEntry, PlayList, Plen2Project, Pose};
use servo_studio::project::{
    Action, Button, Command, Family, JoystickTable, Macro, Project, Run, Servo, ServoProject, Step,
};
use servo_studio::ui::{Action as UiAction, StatusLine, StudioApp, Tab};

const ITEMS: usize = 500;
/// The window sizes every list is checked at: the benchmark's and the default.
const SIZES: [(f32, f32); 2] = [(1600.0, 1000.0), (1100.0, 720.0)];
/// Rows laid out beyond those that fit: the one cut by the edge, and the two
/// egui lays out past it (it rounds the view up, then adds one).
const MARGIN: usize = 3;
/// What the status bar says in these tests (the lists above it end there).
const STATUS: &str = "status line";

fn harness(project: Project, tab: Tab, connect: bool, (width, height): (f32, f32)) -> Harness<'static, StudioApp> {
    let mut app = common::ui::editor(project);
    if connect {
        app.apply(UiAction::ConnectDemo);
        assert!(app.link.is_some(), "{:?}", app.status);
    }
    app.apply(UiAction::ShowTab(tab));
    app.status = Some(StatusLine::new(STATUS, false));
    let mut harness = common::ui::builder((width, height))
        .with_accessibility_check(false)
        .build_ui_state(|ui, app: &mut StudioApp| app.show(ui), app);
    harness.run_steps(3);
    harness
}

/// The rows `rows` matches (those in the list's column), checked to fill the
/// list down to `under` — the widget below it, the status line by default —
/// and to be no more than fit there plus [`MARGIN`]. Returns how many.
fn assert_fills(
    (harness, size): (&Harness<'static, StudioApp>, (f32, f32)),
    rows: By<'_>,
    under: Option<By<'_>>,
    what: &str,
) -> usize {
    let mut rects: Vec<egui::Rect> = harness.query_all(rows).map(|node| node.rect()).collect();
    assert!(rects.len() >= 3, "{what} @{size:?}: only {} rows shown", rects.len());
    // The list's own rows share a left edge; a heading that matches too does not.
    let left = mode(rects.iter().map(|rect| rect.left().round() as i32));
    rects.retain(|rect| (rect.left().round() as i32 - left).abs() <= 1);
    rects.sort_by(|a, b| a.top().total_cmp(&b.top()));
    let first = rects[0].top();
    let pitch = (rects[rects.len() - 1].top() - first) / (rects.len() - 1) as f32;
    let under = under.unwrap_or_else(|| by().label(STATUS));
    let bottom =
        harness.query_all(under).map(|node| node.rect().top()).filter(|top| *top > first).fold(f32::INFINITY, f32::min);
    assert!(bottom.is_finite(), "{what} @{size:?}: nothing found under the list");
    let fit = ((bottom - first) / pitch).floor() as usize;
    let shown = rects.len();
    assert!(
        shown >= fit,
        "{what} @{size:?}: {shown} rows shown where {fit} fit ({:.0} px from the first row to what is under it, {pitch:.1} px a row)",
        bottom - first
    );
    assert!(shown <= fit + MARGIN, "{what} @{size:?}: {shown} of {ITEMS} rows laid out where {fit} fit");
    shown
}

/// The most common value.
fn mode(values: impl Iterator<Item = i32>) -> i32 {
    let mut counts = std::collections::BTreeMap::new();
    for value in values {
        *counts.entry(value).or_insert(0) += 1;
    }
    counts.into_iter().max_by_key(|(_, count)| *count).map(|(value, _)| value).unwrap()
}

fn servos(count: usize) -> Vec<Servo> {
    (0..count).map(|id| Servo::new(u8::try_from(id).unwrap(), format!("舵機{id}"))).collect()
}

#[test]
fn the_servo_sliders_and_settings_fill_the_window() {
    for size in SIZES {
        let project = ServoProject { servos: servos(255), ..ServoProject::default() };
        let mut harness = harness(Project::servo(project), Tab::Servos, false, size);
        let settings = Some(by().label("Servo settings"));
        assert_fills((&harness, size), by().role(Role::Slider).label_contains("舵機"), settings, "servo sliders");
        harness.get_by_label("Servo settings").click();
        // Past the opening animation.
        harness.run_steps(30);
        // Each settings row ends with its remove button; "Add servo" is under them.
        assert_fills(
            (&harness, size),
            by().role(Role::Button).label("×"),
            Some(by().label("Add servo")),
            "servo settings",
        );
    }
}

#[test]
fn the_action_list_and_its_steps_fill_the_window() {
    let steps: Vec<Step> = (0..255u8).map(|servo_id| Step::new(servo_id, 0, 50)).collect();
    let actions: Vec<Action> = (1..=ITEMS)
        .map(|id| Action {
            id: i32::try_from(id).unwrap(),
            caption: format!("動作{id}"),
            steps: if id == 1 { steps.clone() } else { Vec::new() },
        })
        .collect();
    for size in SIZES {
        let project = ServoProject { servos: servos(255), actions: actions.clone(), ..ServoProject::default() };
        let harness = harness(Project::servo(project), Tab::Actions, false, size);
        assert_fills((&harness, size), by().label_contains("動作"), Some(by().label("Graph")), "action list");
        // Each step row ends with its remove button.
        assert_fills((&harness, size), by().role(Role::Button).label("×"), Some(by().label("Add step")), "step table");
    }
}

#[test]
fn the_macro_list_and_its_commands_fill_the_window() {
    let macros: Vec<Macro> = (1..=ITEMS)
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
    for size in SIZES {
        let project = ServoProject { macros: macros.clone(), ..ServoProject::default() };
        let harness = harness(Project::servo(project), Tab::Macros, false, size);
        assert_fills((&harness, size), by().label_contains("巨集"), Some(by().label("Graph")), "macro list");
        // Each command row starts with its drag handle "≡ n".
        assert_fills((&harness, size), by().label_contains("≡ "), Some(by().label("+ Action")), "command table");
    }
}

#[test]
fn the_joystick_tables_and_buttons_fill_the_window() {
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
    let joystick_tables: Vec<JoystickTable> = (1..=ITEMS)
        .map(|id| JoystickTable {
            id: i32::try_from(id).unwrap(),
            caption: format!("表{id}"),
            buttons: if id == 1 { buttons.clone() } else { Vec::new() },
        })
        .collect();
    for size in SIZES {
        let project = ServoProject { joystick_tables: joystick_tables.clone(), ..ServoProject::default() };
        let harness = harness(Project::servo(project), Tab::Joystick, false, size);
        // The live button events are under the tables.
        let events = Some(by().label("Live button events"));
        assert_fills((&harness, size), by().label_contains("表"), events, "table list");
        // Each button row ends with its remove button.
        assert_fills((&harness, size), by().role(Role::Button).label("×"), None, "button table");
    }
}

#[test]
fn the_packet_log_fills_the_window() {
    for size in SIZES {
        let mut harness = harness(Project::servo(ServoProject::default()), Tab::Log, true, size);
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
        // The demo board's own traffic goes on arriving: shown are only these.
        log.set_filter("MarkerResponse");
        harness.run_steps(3);
        assert_fills((&harness, size), by().label_contains("MarkerResponse"), None, "packet log");
    }
}

fn plen2(motions: usize, frames: usize, lists: usize, entries: usize) -> Project {
    let motions = (0..motions)
        .map(|index| Motion {
            slot: u8::try_from(index % 90).unwrap(),
            name: format!("Motion {index}"),
            frames: (0..frames).map(|_| Frame::new(100, Pose::default())).collect(),
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
fn the_plen2_joints_fill_the_window() {
    for size in SIZES {
        let harness = harness(plen2(1, 1, 0, 0), Tab::Joints, false, size);
        let settings = by().label_contains("Joint settings");
        let shown = harness.query_all(by().role(Role::Slider)).count();
        assert_eq!(shown, 18, "all 18 joints fit @{size:?}");
        // The last slider ends above the settings header.
        let last = harness.query_all(by().role(Role::Slider)).map(|node| node.rect().bottom()).fold(0.0, f32::max);
        let header = harness.query_all(settings).map(|node| node.rect().top()).fold(f32::INFINITY, f32::min);
        assert!(last <= header, "the sliders end above the settings @{size:?}");
    }
}

#[test]
fn the_plen2_motion_list_and_frames_fill_the_window() {
    for size in SIZES {
        let harness = harness(plen2(ITEMS, 2, 0, 0), Tab::Motions, false, size);
        assert_fills((&harness, size), by().label_contains("Motion "), Some(by().label("Graph")), "motion list");
        // A motion of 500 frames (more than the robot takes, still drawn): each row has a mirror button.
        let harness = self::harness(plen2(1, ITEMS, 0, 0), Tab::Motions, false, size);
        let lower = Some(by().label("Frame values"));
        assert_fills((&harness, size), by().role(Role::Button).label("Mirror L/R"), lower, "frame table");
    }
}

#[test]
fn the_plen2_play_lists_fill_the_window() {
    for size in SIZES {
        let harness = harness(plen2(1, 1, ITEMS, ITEMS), Tab::PlayLists, false, size);
        assert_fills((&harness, size), by().label_contains("清單"), None, "play lists");
        // Each entry row ends with its remove button.
        assert_fills((&harness, size), by().role(Role::Button).label("×"), None, "play list entries");
    }
}

#[test]
fn the_plen2_slot_map_fills_the_window() {
    // The 9 rows of 10 slots fit in both windows…
    for size in SIZES {
        let harness = harness(plen2(90, 1, 0, 0), Tab::Board, false, size);
        assert_eq!(harness.query_all_by_label_contains("Motion ").count(), 90, "every slot @{size:?}");
    }
    // … and fill a short one, laid out a row of ten at a time.
    let size = (1100.0, 360.0);
    let harness = harness(plen2(90, 1, 0, 0), Tab::Board, false, size);
    let cells = harness.query_all_by_label_contains("Motion ").count();
    assert_eq!(cells % 10, 0, "whole rows of ten");
    // The first column: one cell per row.
    let rows = assert_fills((&harness, size), by().label_contains("Motion "), None, "slot map");
    assert_eq!(rows * 10, cells);
    assert!(cells < 90);
}

#[test]
fn a_drop_down_of_500_actions_lays_out_the_choices_in_view() {
    let actions: Vec<Action> = (1..=ITEMS)
        .map(|id| Action { id: i32::try_from(id).unwrap(), caption: format!("動作{id}"), steps: Vec::new() })
        .collect();
    let macros =
        vec![Macro { id: 1, caption: "巨集".into(), commands: vec![Command::once(Run::Action { action_id: 400 })] }];
    let project = ServoProject { actions, macros, ..ServoProject::default() };
    let mut harness = harness(Project::servo(project), Tab::Macros, false, SIZES[0]);
    // The command's target: the second combo box of its row (after its kind).
    let combos: Vec<_> = harness.query_all(by().role(Role::ComboBox).label("≡ 1")).collect();
    assert_eq!(combos.len(), 2, "kind and target");
    combos[1].click();
    harness.run_steps(3);
    let choices = harness.query_all(by().label_contains("動作")).count();
    assert!(choices >= 3, "the drop-down opened: {choices} choices");
    assert!(choices <= 60, "{choices} of {ITEMS} choices laid out");
    // It opens at the current choice, 400 of 500, and the first ones are not laid out.
    assert!(harness.query_by_label("400 動作400").is_some(), "the current choice is in view");
    assert!(harness.query_by_label("1 動作1").is_none());
    // Picking one sets the command's target.
    harness.get_by_label("401 動作401").click();
    harness.run_steps(2);
    let run = harness.state().document.project.servo.macros[0].commands[0].run;
    assert_eq!(run, Run::Action { action_id: 401 });
}
