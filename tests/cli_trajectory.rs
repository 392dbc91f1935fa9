//! `servo-studio trajectory`: the CSV a script reads, checked against figures
//! worked out by hand from plen2.md §6 and from the servo board's linear
//! moves, and against the official PLEN2 motions' own transition times
//! (`../shared/plen2/motions`, skipped with a notice when absent).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_possible_truncation, clippy::cast_sign_loss)]

use std::path::{Path, PathBuf};
use std::process::Command;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

/// Runs `trajectory ARGS --out DIR/out.csv`; the rows (header first) or the error.
fn trajectory(dir: &Path, args: &[&str]) -> Result<Vec<Vec<String>>, String> {
    let out = dir.join("out.csv");
    let _ = std::fs::remove_file(&out);
    let output = Command::new(EXE).arg("trajectory").args(args).arg("--out").arg(&out).output().unwrap();
    if !output.status.success() {
        return Err(String::from_utf8_lossy(&output.stderr).into_owned());
    }
    let stdout = String::from_utf8_lossy(&output.stdout);
    let text = std::fs::read_to_string(&out).unwrap();
    let rows: Vec<Vec<String>> = text.lines().map(|line| line.split(',').map(str::to_string).collect()).collect();
    assert!(stdout.starts_with(&format!("wrote {} rows", rows.len() - 1)), "{stdout}");
    Ok(rows)
}

fn column(rows: &[Vec<String>], name: &str) -> Vec<i32> {
    let at = rows[0].iter().position(|heading| heading == name).unwrap();
    rows[1..].iter().map(|row| row[at].parse().unwrap()).collect()
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn frame(ms: u32, knee: i32) -> String {
    format!(r#"{{"transition_ms": {ms}, "values_tenths_deg": {{"left_knee_pitch": {knee}}}}}"#)
}

/// A PLEN2 project: slot 0 (100 ms to 100, 64 ms to 300; its frames 0..=1
/// looped once more; then a jump to slot 1), slot 1 (32 ms to −50).
fn plen2_project(dir: &Path) -> PathBuf {
    let text = format!(
        r#"{{"format": "servo-studio-project", "version": 2, "family": "plen2", "plen2": {{"motions": [
            {{"slot": 0, "name": "First", "frames": [{}, {}], "loop_range": {{"begin_frame": 0, "end_frame": 1, "count": 1}}, "jump_slot": 1}},
            {{"slot": 1, "name": "Second", "frames": [{}]}}
        ]}}}}"#,
        frame(100, 100),
        frame(64, 300),
        frame(32, -50)
    );
    write(dir, "plen2.json", &text)
}

#[test]
fn a_plen2_motion_is_one_row_per_cycle_with_its_loop_its_jump_and_where_it_started() {
    let dir = tempfile::tempdir().unwrap();
    let project = plen2_project(dir.path());
    let rows = trajectory(dir.path(), &[project.to_str().unwrap(), "--slot", "0"]).unwrap();
    assert_eq!(rows[0].len(), 19, "t_ms and the 18 joints");
    assert_eq!(rows[0][0], "t_ms");
    // By hand (§6): 0 → 100 in 3 cycles: (100 << 16) / 3 = 2184533 → 33, 66, 99.
    // 100 → 300 in 2 cycles: 200, 300. The loop again from 300: (−200 << 16) / 3
    // = −4369066 (truncated) → 233.33 → 233, 166.67 → 166, 100.00 → 100;
    // then 200, 300; then the jump: 300 → −50 in one cycle.
    assert_eq!(column(&rows, "left_knee_pitch"), [33, 66, 99, 200, 300, 233, 166, 100, 200, 300, -50]);
    assert!(column(&rows, "right_knee_pitch").iter().all(|value| *value == 0));
    let times: Vec<&str> = rows[1..4].iter().map(|row| row[0].as_str()).collect();
    assert_eq!(times, ["0.000", "32.768", "65.536"]);

    // After slot 1 (whose last frame is −50), slot 0's first cycle steps from −50:
    // (150 << 16) / 3 = 3276800 → −50 + 50 = 0.
    let rows = trajectory(dir.path(), &[project.to_str().unwrap(), "--slot", "0", "--from-slot", "1"]).unwrap();
    assert_eq!(column(&rows, "left_knee_pitch")[..3], [0, 50, 100]);

    let error = trajectory(dir.path(), &[project.to_str().unwrap(), "--slot", "9"]).unwrap_err();
    assert!(error.contains("there is no motion in slot 9 (slots: 0, 1)"), "{error}");
    let error = trajectory(dir.path(), &[project.to_str().unwrap(), "--action", "1"]).unwrap_err();
    assert!(error.contains("give --slot N"), "{error}");
}

#[test]
fn a_servo_action_and_macro_are_one_row_per_10_ms_in_degrees() {
    let dir = tempfile::tempdir().unwrap();
    let text = r#"{"format": "servo-studio-project", "version": 2, "family": "servo", "servo": {"project_id": 1,
        "servos": [{"id": 1, "caption": "左肩, front", "home_deg": 10}, {"id": 2, "caption": "", "home_deg": -5}],
        "actions": [
            {"id": 1, "caption": "raise", "steps": [{"servo_id": 1, "degree": 50, "interval_10ms": 10}]},
            {"id": 2, "caption": "lower", "steps": [{"servo_id": 1, "degree": 10, "interval_10ms": 5}, {"servo_id": 2, "degree": 15, "interval_10ms": 2}]}
        ],
        "macros": [{"id": 7, "caption": "wave", "commands": [
            {"kind": "action", "action_id": 1},
            {"kind": "delay", "delay_ms": 50},
            {"kind": "action", "action_id": 2}
        ]}]}}"#;
    let project = write(dir.path(), "servo.json", text);
    let rows = trajectory(dir.path(), &[project.to_str().unwrap(), "--action", "1"]).unwrap();
    // A caption with a comma is quoted: the naive split here sees it as two fields.
    assert_eq!(rows[0][1], "\"1 左肩");
    assert_eq!(rows[0].last().unwrap(), "servo 2");
    // 10 → 50 over 100 ms: 4° every 10 ms; servo 2 holds its home.
    let servo1: Vec<f64> = rows[1..].iter().map(|row| row[1].parse().unwrap()).collect();
    assert_eq!(servo1, [10.0, 14.0, 18.0, 22.0, 26.0, 30.0, 34.0, 38.0, 42.0, 46.0, 50.0]);
    assert!(rows[1..].iter().all(|row| row[2] == "-5.00"));

    let rows = trajectory(dir.path(), &[project.to_str().unwrap(), "--macro", "7"]).unwrap();
    // 100 ms up, 50 ms wait, then 50 ms down (servo 2: 20 ms to 15): 200 ms, 21 rows.
    assert_eq!(rows.len() - 1, 21);
    let at = |t: usize, column: usize| rows[1 + t / 10][column].parse::<f64>().unwrap();
    assert_eq!(at(100, 1), 50.0);
    assert_eq!(at(150, 1), 50.0, "the delay holds");
    assert_eq!(at(170, 1), 34.0, "two fifths of the way down");
    assert_eq!(at(200, 1), 10.0);
    assert_eq!(at(170, 2), 15.0, "servo 2 arrived after 20 ms");
    assert_eq!(at(160, 2), 5.0);
    assert!(trajectory(dir.path(), &[project.to_str().unwrap(), "--macro", "8"]).unwrap_err().contains("no macro 8"));
}

#[test]
fn the_official_motions_take_the_cycles_their_transitions_say() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/plen2/motions");
    if !folder.is_dir() {
        eprintln!("skipped: {} is absent", folder.display());
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut checked = 0;
    for entry in std::fs::read_dir(&folder).unwrap() {
        let path = entry.unwrap().path();
        let motion: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let slot = motion["slot"].as_u64().unwrap().to_string();
        let codes = motion["codes"].as_array().unwrap();
        let rows = trajectory(dir.path(), &[path.to_str().unwrap(), "--slot", &slot, "--seconds", "2"]).unwrap();
        // Worked out from the file alone: (ms / 32) & 0xFF cycles per frame.
        let cycles: usize = motion["frames"]
            .as_array()
            .unwrap()
            .iter()
            .map(|frame| ((frame["transition_time_ms"].as_u64().unwrap() / 32) & 0xff) as usize)
            .sum();
        let limit = (2000.0 / 32.768) as usize + 1;
        if codes.is_empty() {
            assert_eq!(rows.len() - 1, cycles.min(limit), "{}", path.display());
        } else {
            // The walks loop forever: cut at --seconds.
            assert_eq!(rows.len() - 1, limit, "{}", path.display());
        }
        // The last frame's values are reached (to within the floor of a step) when it ends.
        if codes.is_empty() && cycles < limit {
            let last = motion["frames"].as_array().unwrap().last().unwrap()["outputs"].as_array().unwrap().clone();
            for output in last {
                let name = output["device"].as_str().unwrap();
                let value = output["value"].as_i64().unwrap() as i32;
                let reached = *column(&rows, name).last().unwrap();
                assert!((reached - value).abs() <= 1, "{}: {name} ends at {reached}, not {value}", path.display());
            }
        }
        checked += 1;
    }
    assert_eq!(checked, 90);
}

/// plen2.md §6's edges, with figures worked by hand: a loop of count 0 runs
/// forever (and says so), a jump to a slot ≥ 90 replays the motion, a frame
/// of 0 cycles is skipped but the next steps from it.
#[test]
fn motions_on_the_firmwares_edges_play_as_the_robot_plays_them() {
    let dir = tempfile::tempdir().unwrap();
    let text = format!(
        r#"{{"format": "servo-studio-project", "version": 2, "family": "plen2", "plen2": {{"motions": [
            {{"slot": 0, "name": "Forever", "frames": [{}, {}, {}], "loop_range": {{"begin_frame": 0, "end_frame": 1, "count": 0}}}},
            {{"slot": 1, "name": "Beyond", "frames": [{}, {}], "jump_slot": 90}},
            {{"slot": 2, "name": "Skip", "frames": [{}, {}, {}]}}
        ]}}}}"#,
        frame(100, 100),
        frame(100, 300),
        frame(100, 0),
        frame(64, 100),
        frame(32, 50),
        frame(100, 100),
        frame(0, 300),
        frame(100, 210),
    );
    let project = write(dir.path(), "edges.json", &text);
    let project = project.to_str().unwrap();
    // Joint values are relative to home; the knee's column is the frame value itself.
    let out = dir.path().join("out.csv");
    let output = Command::new(EXE)
        .args(["trajectory", project, "--slot", "0", "--seconds", "0.39", "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(String::from_utf8_lossy(&output.stderr).contains("motion 0 never ends"), "said, not only cut");
    let rows: Vec<Vec<String>> = std::fs::read_to_string(&out)
        .unwrap()
        .lines()
        .map(|line| line.split(',').map(str::to_string).collect())
        .collect();
    assert_eq!(column(&rows, "left_knee_pitch"), [33, 66, 99, 166, 233, 299, 233, 166, 100, 166, 233, 299]);

    let rows = trajectory(dir.path(), &[project, "--slot", "1", "--seconds", "0.29"]).unwrap();
    assert_eq!(column(&rows, "left_knee_pitch"), [50, 100, 50, 75, 100, 50, 75, 100, 50]);

    let rows = trajectory(dir.path(), &[project, "--slot", "2"]).unwrap();
    assert_eq!(column(&rows, "left_knee_pitch"), [33, 66, 99, 270, 240, 210], "300 never shown; 210 from it");
}
