//! One test per validation rule: each builds a valid project, breaks one thing,
//! and checks that exactly that problem is reported, with its location.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::needless_pass_by_value)]

use servo_studio::project::{
    Action, Button, Command, JoystickTable, Macro, Problem, RigAxis, RigJoint, Run, Servo, ServoProject, Severity,
    Step, has_errors, validate_servo,
};

fn step(servo_id: u8, degree: i16) -> Step {
    Step::new(servo_id, degree, 50)
}

/// A small valid project: two servos, two actions, two macros, one table.
fn valid() -> ServoProject {
    ServoProject {
        meshes: Vec::new(),
        project_id: 1,
        servos: vec![Servo::new(1, "左肩"), Servo::new(2, "右肩")],
        actions: vec![
            Action { id: 1, caption: "舉手".into(), steps: vec![step(1, -90), step(2, 45)] },
            Action { id: 42, caption: "放下".into(), steps: vec![step(1, 0)] },
        ],
        macros: vec![
            Macro {
                id: 100,
                caption: "巨集1".into(),
                commands: vec![
                    Command::once(Run::Action { action_id: 1 }),
                    Command::once(Run::Delay { delay_ms: 200 }),
                    Command::once(Run::Action { action_id: 42 }),
                ],
            },
            Macro { id: 101, caption: "巨集2".into(), commands: vec![Command::once(Run::Macro { macro_id: 100 })] },
        ],
        joystick_tables: vec![JoystickTable {
            id: 1,
            caption: "遙控器".into(),
            buttons: vec![Button {
                id: 0x8000_0001,
                caption: "A".into(),
                press_macro: Some(100),
                long_press_macro: None,
                release_macro: None,
                uninterruptible: false,
            }],
        }],
        active_table: Some(1),
    }
}

/// The single problem `project` has; fails if it has none or several.
fn only_problem(project: &ServoProject) -> Problem {
    let problems = validate_servo(project);
    assert_eq!(problems.len(), 1, "expected exactly one problem, got {problems:#?}");
    problems.into_iter().next().unwrap()
}

fn only_error_text(project: &ServoProject) -> String {
    let problem = only_problem(project);
    assert_eq!(problem.severity, Severity::Error, "{problem}");
    problem.to_string()
}

#[test]
fn the_base_project_is_valid() {
    assert_eq!(validate_servo(&valid()), []);
}

#[test]
fn dangling_action_reference_names_macro_and_command() {
    let mut project = valid();
    project.actions.remove(1);
    assert_eq!(only_error_text(&project), "error: macro 100 \"巨集1\", command 3: action 42 does not exist");
}

#[test]
fn dangling_macro_references_in_commands_buttons_and_active_table() {
    let mut project = valid();
    project.macros[1].commands[0] = Command::once(Run::Macro { macro_id: 9 });
    assert_eq!(only_error_text(&project), "error: macro 101 \"巨集2\", command 1: macro 9 does not exist");

    let mut project = valid();
    project.joystick_tables[0].buttons[0].release_macro = Some(555);
    assert_eq!(
        only_error_text(&project),
        "error: joystick table 1 \"遙控器\", button 0x80000001 \"A\": release macro 555 does not exist"
    );

    let mut project = valid();
    project.active_table = Some(2);
    assert_eq!(only_error_text(&project), "error: project: active joystick table 2 does not exist");
}

#[test]
fn duplicate_ids_of_every_kind() {
    let mut project = valid();
    project.servos.push(Servo::new(2, "again"));
    assert!(only_error_text(&project).contains("duplicate servo id 2"));

    let mut project = valid();
    project.actions.push(Action { id: 1, caption: "又一個".into(), steps: vec![step(2, 0)] });
    assert!(only_error_text(&project).contains("action 1 \"又一個\": duplicate action id 1"));

    let mut project = valid();
    project.macros[1].id = 100;
    project.macros[1].commands.clear();
    let problems = validate_servo(&project);
    assert!(problems.iter().any(|p| p.to_string().contains("duplicate macro id 100")), "{problems:#?}");

    let mut project = valid();
    let table = project.joystick_tables[0].clone();
    project.joystick_tables.push(table);
    assert!(only_error_text(&project).contains("duplicate joystick table id 1"));

    let mut project = valid();
    let button = project.joystick_tables[0].buttons[0].clone();
    project.joystick_tables[0].buttons.push(button);
    assert!(only_error_text(&project).contains("duplicate button id 0x80000001"));
}

#[test]
fn unknown_servo_in_a_step() {
    let mut project = valid();
    project.actions[0].steps[1].servo_id = 7;
    assert_eq!(only_error_text(&project), "error: action 1 \"舉手\", step 2: servo 7 does not exist");
}

#[test]
fn the_same_servo_twice_in_one_action() {
    let mut project = valid();
    project.actions[0].steps[1].servo_id = 1;
    assert_eq!(
        only_error_text(&project),
        "error: action 1 \"舉手\", step 2: servo 1 already has a step in this action"
    );
}

#[test]
fn macro_cycles_direct_and_indirect() {
    let mut project = valid();
    project.macros[0].commands.push(Command::once(Run::Macro { macro_id: 101 }));
    // Reported once, at the command that closes the loop.
    assert_eq!(
        only_error_text(&project),
        "error: macro 101 \"巨集2\", command 1: macro cycle 100 → 101 → 100: a macro must not reach itself"
    );

    let mut project = valid();
    project.macros[0].commands.push(Command::once(Run::Macro { macro_id: 100 }));
    assert_eq!(
        only_error_text(&project),
        "error: macro 100 \"巨集1\", command 4: macro cycle 100 → 100: a macro must not reach itself"
    );
}

fn rig(parent: Option<u8>) -> Option<RigJoint> {
    Some(RigJoint {
        parent,
        offset_mm: [0, 30, 0],
        axis: RigAxis::Y,
        reversed: false,
        straight_deg: 0,
        mirror: None,
        end: None,
    })
}

#[test]
fn a_rig_with_an_unknown_parent_or_a_cycle_is_refused_with_its_location() {
    // A valid rig: 2 on 1, 1 on the body.
    let mut project = valid();
    project.servos[0].rig = rig(None);
    project.servos[1].rig = rig(Some(1));
    assert!(validate_servo(&project).is_empty(), "{:?}", validate_servo(&project));

    let mut unknown = project.clone();
    unknown.servos[1].rig = rig(Some(9));
    assert_eq!(
        only_error_text(&unknown),
        "error: servo 2 \"右肩\": its rig is mounted on servo 9, which is not in the rig: rig that servo or pick another parent"
    );
    // A parent that exists but has no rig is not in the rig either.
    let mut unrigged = project.clone();
    unrigged.servos[0].rig = None;
    assert!(only_error_text(&unrigged).contains("mounted on servo 1, which is not in the rig"));

    let mut ring = project.clone();
    ring.servos[0].rig = rig(Some(2));
    // Said once, at the first servo of the ring.
    assert_eq!(
        only_error_text(&ring),
        "error: servo 1 \"左肩\": rig cycle 1 → 2 → 1: a servo cannot be mounted on itself"
    );
    let mut itself = project;
    itself.servos[0].rig = rig(Some(1));
    assert_eq!(
        only_error_text(&itself),
        "error: servo 1 \"左肩\": rig cycle 1 → 1: a servo cannot be mounted on itself"
    );
}

#[test]
fn captions_longer_than_32_bytes() {
    // 11 CJK characters are 33 UTF-8 bytes.
    let mut project = valid();
    project.macros[0].caption = "一二三四五六七八九十壹".into();
    assert!(only_error_text(&project).contains("caption is 33 UTF-8 bytes; the board stores at most 32"));

    let mut project = valid();
    project.servos[0].caption = "x".repeat(33);
    assert!(only_error_text(&project).starts_with("error: servo 1"));

    let mut project = valid();
    project.joystick_tables[0].buttons[0].caption = "按".repeat(11);
    assert!(only_error_text(&project).contains("button 0x80000001"));

    // Exactly 32 bytes is fine.
    let mut project = valid();
    project.actions[0].caption = "x".repeat(32);
    assert_eq!(validate_servo(&project), []);
}

#[test]
fn ratio_outside_1_to_100() {
    for ratio_percent in [0u8, 101, 255] {
        let mut project = valid();
        project.macros[0].commands[0].ratio_percent = ratio_percent;
        let text = only_error_text(&project);
        assert!(text.contains(&format!("ratio {ratio_percent} % is outside 1..=100")), "{text}");
    }
}

#[test]
fn values_outside_their_field_range() {
    let mut project = valid();
    project.macros[0].commands[0].loop_count = 0;
    assert!(only_error_text(&project).contains("loop count 0 must be 1 or more"));

    let mut project = valid();
    project.macros[0].commands[1].run = Run::Delay { delay_ms: -5 };
    assert!(only_error_text(&project).contains("delay -5 ms is negative"));

    let mut project = valid();
    project.actions[0].steps[0].interval_10ms = -1;
    assert!(only_error_text(&project).contains("interval -1 × 10 ms is negative"));

    let mut project = valid();
    project.servos[1].id = 255;
    project.actions[0].steps[1].servo_id = 255;
    assert!(only_error_text(&project).contains("servo id 255 is reserved"));

    let mut project = valid();
    project.actions[1].id = 0;
    project.macros[0].commands[2] = Command::once(Run::Action { action_id: 0 });
    assert!(only_error_text(&project).contains("action id must be 1 or more"));

    let mut project = valid();
    project.servos[0].min_deg = 10;
    project.servos[0].max_deg = -10;
    project.actions.clear();
    project.macros.clear();
    project.joystick_tables.clear();
    project.active_table = None;
    assert!(only_error_text(&project).contains("min 10° is above max -10°"));

    let mut project = valid();
    project.servos[0].home_deg = 200;
    assert!(only_error_text(&project).contains("home 200° is outside the limits -180°..180°"));

    let mut project = valid();
    project.servos[0].min_deg = -45;
    assert_eq!(
        only_error_text(&project),
        "error: action 1 \"舉手\", step 1: -90° is outside servo 1's limits -45°..180°"
    );

    // A total run time the board's 32-bit totalInterval cannot hold.
    let mut project = valid();
    project.macros.truncate(1); // macro 101 would overflow too, by running macro 100
    project.actions[0].steps[0].interval_10ms = i16::MAX;
    project.macros[0].commands[0] =
        Command { run: Run::Action { action_id: 1 }, ratio_percent: 1, loop_count: i16::MAX, stored_total_ms: None };
    assert!(only_error_text(&project).contains("more than the board can count"));
}

#[test]
fn every_problem_is_reported_not_just_the_first() {
    let mut project = valid();
    project.actions.remove(1); // dangling 42
    project.macros[0].commands[0].ratio_percent = 0;
    project.servos[0].caption = "x".repeat(40);
    project.active_table = Some(9);
    let problems = validate_servo(&project);
    assert_eq!(problems.len(), 4, "{problems:#?}");
    assert!(has_errors(&problems));
}

#[test]
fn warnings_alone_are_not_errors() {
    let mut project = valid();
    project.joystick_tables[0].buttons[0].press_macro = None;
    let problem = only_problem(&project);
    assert_eq!(problem.severity, Severity::Warning);
    assert_eq!(problem.to_string(), "warning: joystick table 1 \"遙控器\", button 0x80000001 \"A\": runs no macro");
    assert!(!has_errors(&[problem]));
}

#[test]
fn a_stored_total_unlike_the_derived_one_is_a_warning_naming_both() {
    let mut project = valid();
    project.macros[0].commands[0].stored_total_ms = Some(1234);
    let problems = validate_servo(&project);
    let texts: Vec<String> = problems.iter().map(ToString::to_string).collect();
    assert_eq!(problems.len(), 1, "{texts:?}");
    assert_eq!(problems[0].severity, Severity::Warning);
    assert!(texts[0].contains("stored a total of 1234 ms") && texts[0].contains("derives"), "{}", texts[0]);
}
