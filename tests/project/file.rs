//! The project file: round trips, the checked-in fixture, and derived timing.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::needless_pass_by_value)]

use servo_studio::project::plen2::{Joint, Pose};
use servo_studio::project::{
    self, Action, Button, Command, Family, JoystickTable, LoadError, Macro, Project, Run, Servo, ServoProject, Step,
    Timing,
};

fn fixture_path() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/project-v1.json")
}

/// A project that uses every field, with CJK captions and extreme values.
fn rich_project() -> ServoProject {
    let mut servos: Vec<Servo> = (0..8u8).map(|id| Servo::new(id, format!("關節{id}"))).collect();
    servos[0].calibration_offset_deg = -12;
    servos[0].min_deg = -120;
    servos[0].max_deg = 120;
    servos[0].home_deg = -5;
    ServoProject {
        meshes: Vec::new(),
        project_id: i32::MAX,
        servos,
        actions: vec![
            Action {
                id: 1, caption: "動作一二三四五六七八九十".into(), steps: vec![Step::new(0, -120, 0)]
            },
            Action { id: i32::MAX, caption: String::new(), steps: vec![] },
        ],
        macros: vec![Macro {
            id: 7,
            caption: "巨集".into(),
            commands: vec![
                Command {
                    run: Run::Action { action_id: 1 },
                    ratio_percent: 1,
                    loop_count: i16::MAX,
                    stored_total_ms: None,
                },
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
    }
}

#[test]
fn save_then_load_is_lossless_including_cjk_captions() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("機器人.json");
    let original = Project::servo(rich_project());
    project::save(&path, &original).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("動作一二三四五六七八九十"), "CJK is stored as text, not escapes");
    assert!(text.starts_with(
        "{\n  \"format\": \"servo-studio-project\",\n  \"version\": 2,\n  \"family\": \"servo\",\n  \"servo\": {"
    ));
    // Empty sections of other families are not written.
    assert!(!text.contains("\"plen2\"") && !text.contains("\"rflex\""), "{text}");
    assert_eq!(project::load(&path).unwrap(), original);
}

#[test]
fn saving_over_an_existing_file_replaces_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("robot.json");
    project::save(&path, &Project::default()).unwrap();
    let project = Project::servo(rich_project());
    project::save(&path, &project).unwrap();
    assert_eq!(project::load(&path).unwrap(), project);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "no temporary file is left behind");
}

#[test]
fn the_checked_in_version_1_fixture_keeps_loading_and_saves_as_version_2() {
    let document = project::load(&fixture_path()).unwrap();
    assert_eq!(document.family, Family::Servo);
    let loaded = &document.servo;
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
    assert_eq!(project::validate(&document), []);
    // What this build writes for it is version 2, and loads back identically.
    let text = project::to_json(&document);
    assert!(text.contains("\"version\": 2") && text.contains("\"family\": \"servo\""), "{text}");
    assert_eq!(project::from_json(&text).unwrap(), document);
}

#[test]
fn the_fixtures_macro_totals_follow_the_documented_semantics() {
    let loaded = project::load(&fixture_path()).unwrap().servo;
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
    assert!(matches!(err, LoadError::Read(project::input::ReadError::Io { .. })));
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

fn fixture_v2_path() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/project-v2.json")
}

#[test]
fn the_checked_in_version_2_fixture_loads_every_section() {
    let document = project::load(&fixture_v2_path()).unwrap();
    assert_eq!(document.family, Family::Servo);
    // A total stored by a board is kept; a command without one derives it.
    let commands = &document.servo.macros[0].commands;
    assert_eq!(commands[0].stored_total_ms, Some(2000));
    assert_eq!(commands[1].stored_total_ms, None);
    assert_eq!(document.servo.servos[1].min_deg, -180, "omitted limits take their defaults");
    // The other families' sections are kept as they are.
    let motion = &document.plen2.motions[0];
    assert_eq!((motion.slot, motion.name.as_str(), motion.frames.len()), (70, "Walk Forward", 2));
    assert_eq!(motion.frames[0].values_tenths_deg.get(Joint::LeftKneePitch), -150);
    assert_eq!(motion.frames[0].values_tenths_deg.get(Joint::RightKneePitch), 150);
    assert_eq!(motion.frames[1].values_tenths_deg, Pose::default(), "an omitted joint is 0");
    assert_eq!(motion.loop_range.unwrap().count, 255);
    assert_eq!(document.plen2.play_lists[0].entries[0].plays, 3);
    assert_eq!(document.plen2.joints[0].home_tenths_deg, 500);
    assert_eq!(document.rflex.robot.conversion().angle_units_per_rad, 34000.5);
    assert!(!document.rflex.drive.sonar_on_connect);
    // Validation is the document's family's. The stored total equals the
    // derived one (500 ms × 2 loops at 50 % = 2000 ms), so there is no warning.
    assert_eq!(project::validate(&document), []);
    assert_eq!(project::from_json(&project::to_json(&document)).unwrap(), document);
}

#[test]
fn validation_follows_the_documents_family() {
    let mut document = project::load(&fixture_v2_path()).unwrap();
    document.plen2.motions[0].frames[1].transition_ms = 9000;
    assert_eq!(project::validate(&document), [], "a servo document does not validate its PLEN2 section");
    document.family = Family::Plen2;
    let texts: Vec<String> = project::validate(&document).iter().map(ToString::to_string).collect();
    assert_eq!(texts, ["error: motion 70 \"Walk Forward\", frame 2: transition_ms 9000 is outside 32..=8191"]);
    document.family = Family::Rflex;
    document.rflex.drive.max_speed_m_per_s = 0.0;
    let texts: Vec<String> = project::validate(&document).iter().map(ToString::to_string).collect();
    assert_eq!(texts, ["error: robot: max_speed_m_per_s must be a positive number"]);
}

#[test]
fn a_family_section_is_written_for_an_empty_project_of_that_family() {
    for &family in Family::all() {
        let text = project::to_json(&Project::empty(family));
        assert!(text.contains(&format!("\"family\": \"{}\"", family.tag())), "{text}");
        assert!(text.contains(&format!("\"{}\": {{", family.tag())), "{text}");
        assert_eq!(project::from_json(&text).unwrap(), Project::empty(family));
    }
}

#[test]
fn the_sample_robot_is_a_valid_16_servo_biped() {
    let sample = servo_studio::ui::sample_project();
    assert_eq!(sample.family, Family::Servo);
    assert_eq!(sample.servo.servos.len(), 16);
    assert!(sample.servo.servos.iter().all(|servo| servo.caption.chars().any(|c| c > '\u{2e80}')), "CJK captions");
    assert!(sample.servo.actions.len() >= 3 && !sample.servo.macros.is_empty());
    assert_eq!(sample.servo.joystick_tables.len(), 1);
    assert_eq!(project::validate(&sample), []);
}
