//! The project file: round trips, the checked-in fixture, and derived timing.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::needless_pass_by_value)]

use servo_studio::project::{
    self, Action, Button, Command, JoystickTable, LoadError, Macro, Project, Run, Servo, Step, Timing,
};

fn fixture_path() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/project-v1.json")
}

/// A project that uses every field, with CJK captions and extreme values.
fn rich_project() -> Project {
    let mut servos: Vec<Servo> = (0..8u8).map(|id| Servo::new(id, format!("關節{id}"))).collect();
    servos[0].calibration_offset_deg = -12;
    servos[0].min_deg = -120;
    servos[0].max_deg = 120;
    servos[0].home_deg = -5;
    Project {
        project_id: i32::MAX,
        servos,
        actions: vec![
            Action {
                id: 1,
                caption: "動作一二三四五六七八九十".into(),
                steps: vec![Step { servo_id: 0, degree: -120, interval_10ms: 0 }],
            },
            Action { id: i32::MAX, caption: String::new(), steps: vec![] },
        ],
        macros: vec![Macro {
            id: 7,
            caption: "巨集".into(),
            commands: vec![
                Command { run: Run::Action { action_id: 1 }, ratio_percent: 1, loop_count: i16::MAX },
                Command::once(Run::Delay { delay_ms: 0 }),
                Command::once(Run::Macro { macro_id: 8 }),
            ],
        }],
        joystick_tables: vec![JoystickTable {
            id: 3,
            caption: "手把".into(),
            buttons: vec![Button {
                id: u32::MAX,
                caption: "開始".into(),
                press_macro: Some(7),
                long_press_macro: None,
                release_macro: Some(-1),
                uninterruptible: true,
            }],
        }],
        active_table: Some(3),
        ..Project::default()
    }
}

#[test]
fn save_then_load_is_lossless_including_cjk_captions() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("機器人.json");
    let original = rich_project();
    project::save(&path, &original).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("動作一二三四五六七八九十"), "CJK is stored as text, not escapes");
    assert!(text.starts_with("{\n  \"format\": \"servo-studio-project\",\n  \"version\": 1,"));
    assert_eq!(project::load(&path).unwrap(), original);
}

#[test]
fn saving_over_an_existing_file_replaces_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("robot.json");
    project::save(&path, &Project::default()).unwrap();
    let project = rich_project();
    project::save(&path, &project).unwrap();
    assert_eq!(project::load(&path).unwrap(), project);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "no temporary file is left behind");
}

#[test]
fn the_checked_in_version_1_fixture_keeps_loading() {
    let loaded = project::load(&fixture_path()).unwrap();
    assert_eq!(loaded.project_id, 20261121);
    assert_eq!(loaded.servos.len(), 3);
    assert_eq!(loaded.servos[2].caption, "頭部");
    // Omitted fields take their documented defaults.
    assert_eq!(loaded.servos[2].calibration_offset_deg, 0);
    assert_eq!(loaded.servos[2].home_deg, 0);
    assert_eq!(loaded.macros[0].caption, "巨集1");
    assert_eq!(loaded.macros[0].commands[1], Command::once(Run::Delay { delay_ms: 500 }));
    assert_eq!(loaded.joystick_tables[0].buttons[1].id, 0x8000_0001);
    assert_eq!(loaded.active_table, Some(1));
    assert_eq!(project::validate(&loaded), []);
    // And what this build writes for it loads back identically.
    assert_eq!(project::from_json(&project::to_json(&loaded)).unwrap(), loaded);
}

#[test]
fn the_fixtures_macro_totals_follow_the_documented_semantics() {
    let loaded = project::load(&fixture_path()).unwrap();
    let timing = Timing::new(&loaded);
    let commands = &loaded.macros[0].commands;
    // Action 1: longest step 100 × 10 ms = 1000 ms, once at 100 %.
    assert_eq!(timing.command_total_ms(&commands[0]), Ok(1000));
    assert_eq!(timing.command_total_ms(&commands[1]), Ok(500));
    // Action 2: 200 ms × 3 loops × 100 / 50 % = 1200 ms.
    assert_eq!(timing.command_total_ms(&commands[2]), Ok(1200));
    assert_eq!(timing.macro_total_ms(100), Ok(2700));
    // Macro 101 runs macro 100 twice at full speed.
    assert_eq!(timing.macro_total_ms(101), Ok(5400));
}

#[test]
fn a_missing_file_names_the_path() {
    let err = project::load(std::path::Path::new("/nonexistent/robot.json")).unwrap_err();
    assert!(matches!(err, LoadError::Io { .. }));
    assert!(err.to_string().contains("/nonexistent/robot.json"), "{err}");
}

#[test]
fn a_value_out_of_its_type_range_is_a_positioned_error() {
    let text = r#"{"format": "servo-studio-project", "version": 1,
"servos": [{"id": 300}]}"#;
    match project::from_json(text) {
        Err(LoadError::Syntax { line: 2, message, .. }) => assert!(message.contains("300"), "{message}"),
        other => panic!("expected a syntax error on line 2, got {other:?}"),
    }
}
