//! The `servo-studio` command line, run as a user runs it.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::needless_pass_by_value)]

use std::process::{Command, Output};

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_servo-studio")).args(args).output().unwrap()
}

fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

fn fixture() -> String {
    format!("{}/tests/fixtures/project-v1.json", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn help_and_version() {
    let help = run(&["--help"]);
    assert!(help.status.success());
    assert!(stdout(&help).contains("check"), "{}", stdout(&help));
    let version = run(&["--version"]);
    assert!(version.status.success());
    // The version, and the commit it was built from (tests/cli/installed.rs checks which).
    let said = stdout(&version);
    assert!(said.starts_with(&format!("servo-studio {} (", env!("CARGO_PKG_VERSION"))), "{said}");
}

#[test]
fn check_of_a_valid_project_exits_0() {
    let output = run(&["check", &fixture()]);
    assert!(output.status.success(), "{}", stdout(&output));
    assert!(stdout(&output).ends_with("0 error(s), 0 warning(s)\n"), "{}", stdout(&output));
}

#[test]
fn check_prints_every_problem_and_exits_1_on_errors() {
    let text = std::fs::read_to_string(fixture()).unwrap();
    let broken =
        text.replace("\"action_id\": 2,", "\"action_id\": 42,").replace("\"active_table\": 1", "\"active_table\": 5");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("broken.json");
    std::fs::write(&path, broken).unwrap();
    let output = run(&["check", path.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(1));
    let printed = stdout(&output);
    assert!(printed.contains("error: macro 100 \"巨集1\", command 3: action 42 does not exist"), "{printed}");
    assert!(printed.contains("error: project: active joystick table 5 does not exist"), "{printed}");
    assert!(printed.contains("2 error(s)"), "{printed}");
}

/// The editor's own settings are checked too: a Mirror L/R twin outside the
/// rig and a gamepad button firing a macro the project lacks are warnings.
#[test]
fn check_warns_of_a_twin_outside_the_rig_and_a_gamepad_button_firing_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("pad.json");
    std::fs::write(
        &path,
        r#"{"format": "servo-studio-project", "version": 2, "family": "servo",
        "servo": {"servos": [{"id": 1, "caption": "臂", "rig": {"axis": "y", "mirror": 7}}]},
        "gamepad": {"servo": {"buttons": [{"button": 304, "fire": {"macro": 5}}]}}}"#,
    )
    .unwrap();
    let output = run(&["check", path.to_str().unwrap()]);
    assert!(output.status.success(), "warnings only: {}", stdout(&output));
    let printed = stdout(&output);
    assert!(printed.contains("warning: servo 1 \"臂\": its Mirror L/R twin is servo 7"), "{printed}");
    assert!(printed.contains("warning: gamepad button 0x130: macro 5 does not exist"), "{printed}");
    assert!(printed.ends_with("0 error(s), 2 warning(s)\n"), "{printed}");
}

#[test]
fn check_of_a_malformed_file_gives_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.json");
    std::fs::write(&path, "{\"format\": \"servo-studio-project\",\n \"servos\": [ }").unwrap();
    let output = run(&["check", path.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(1));
    let printed = String::from_utf8_lossy(&output.stderr);
    assert!(printed.contains("line 2, column"), "{printed}");
}

#[test]
fn check_reads_a_plen2_motion_json_and_locates_its_problems() {
    let frame = |ms: u32| {
        format!(r#"{{"transition_time_ms": {ms}, "outputs": [{{"device": "left_knee_pitch", "value": 100}}]}}"#)
    };
    let text = format!(
        r#"{{"slot": 70, "name": "Walk Forward", "codes": [], "frames": [{}, {}, {}]}}"#,
        frame(100),
        frame(100),
        frame(9000)
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("70_Walk_Forward.json");
    std::fs::write(&path, text).unwrap();
    let output = run(&["check", path.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(1));
    let printed = stdout(&output);
    assert!(
        printed.contains("error: motion 70 \"Walk Forward\", frame 3: transition_ms 9000 is outside 32..=8191"),
        "{printed}"
    );
    assert!(printed.contains("1 error(s)"), "{printed}");
}

/// `check` takes a show file (version 3): each device's project is checked as
/// a project is, and every cue against what its device holds — every problem
/// said, not only the first; a good show passes.
#[test]
fn check_takes_a_show_and_says_every_problem_of_its_devices_and_cues() {
    use servo_studio::project::{Family, Project};
    use servo_studio::show::{Cue, Device, Place, Show, Start};
    let dir = tempfile::tempdir().unwrap();
    let skull = servo_studio::project::load(std::path::Path::new(&fixture())).unwrap();
    let macro_id = skull.servo.macros[0].id;
    let device = |name: &str, project: Project| Device {
        name: name.into(),
        port: None,
        place: Place::default(),
        project,
        play_on_without: false,
    };
    let good = Show {
        devices: vec![device("skull", skull.clone()), device("base", Project::empty(Family::Rflex))],
        sound: None,
        cues: vec![Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(macro_id) }],
    };
    let file = dir.path().join("good.json");
    std::fs::write(&file, good.to_json()).unwrap();
    let output = run(&["check", file.to_str().unwrap()]);
    assert!(output.status.success(), "{}", stdout(&output));
    assert!(stdout(&output).ends_with("0 error(s), 0 warning(s)\n"), "{}", stdout(&output));
    // Three things wrong at once, and a key misspelt: each said.
    let mut text: serde_json::Value = serde_json::from_str(&good.to_json()).unwrap();
    text["cues"] = serde_json::json!([
        { "device": "skull", "at_ms": 0, "macro": 999 },
        { "device": "nobody", "at_ms": 500, "macro": 1 },
    ]);
    text["devices"][0]["project"]["servo"]["servos"][0]["id"] = serde_json::json!(200);
    text["cuess"] = serde_json::json!([]);
    let bad = dir.path().join("bad.json");
    std::fs::write(&bad, serde_json::to_string_pretty(&text).unwrap()).unwrap();
    let output = run(&["check", bad.to_str().unwrap()]);
    let said = stdout(&output);
    assert_eq!(output.status.code(), Some(1), "{said}");
    assert!(said.contains("cuess") && said.contains("unknown key"), "the misspelt key: {said}");
    assert!(said.contains("device \"skull\""), "the device's own project checked: {said}");
    assert!(said.contains("to start macro 999, which it does not hold"), "{said}");
    assert!(said.contains("\"nobody\", which is not a device of the show"), "{said}");
    assert!(!said.contains("expected servo-studio-project"), "taken as a show: {said}");
}
