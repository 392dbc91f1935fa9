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

/// The official motion files in name order, or `None` (said on stderr) when
/// `../shared` is absent.
fn official_motions() -> Option<Vec<PathBuf>> {
    crate::common::official_motion_files()
}

#[test]
fn the_official_motions_take_the_cycles_their_transitions_say() {
    let Some(files) = official_motions() else { return };
    let dir = tempfile::tempdir().unwrap();
    let mut checked = 0;
    for path in files {
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

/// Runs `fit RECORDING ARGS --out OUT`: stdout, or stderr on failure.
fn fit(recording: &Path, out: &Path, args: &[&str]) -> Result<String, String> {
    let output = Command::new(EXE).arg("fit").arg(recording).args(args).arg("--out").arg(out).output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    if output.status.success() { Ok(stdout) } else { Err(String::from_utf8_lossy(&output.stderr).into_owned()) }
}

/// A CSV as `trajectory` writes it, from rows of (t_ms, values).
fn csv(header: &str, rows: impl Iterator<Item = (f64, Vec<f64>)>) -> String {
    let mut text = format!("t_ms,{header}\n");
    for (t_ms, values) in rows {
        let values: Vec<String> = values.iter().map(|value| format!("{value:.2}")).collect();
        text.push_str(&format!("{t_ms:.3},{}\n", values.join(",")));
    }
    text
}

fn frames_of(motion_json: &Path) -> usize {
    let value: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(motion_json).unwrap()).unwrap();
    value["frames"].as_array().unwrap().len()
}

/// Every joint's column of two trajectories: same length, within `tolerance` at every cycle.
fn within(wanted: &[Vec<String>], played: &[Vec<String>], tolerance: f64, what: &str) {
    assert_eq!(wanted.len(), played.len(), "{what}: as many cycles");
    assert_eq!(wanted[0], played[0], "{what}: the same columns");
    for (row, (a, b)) in wanted.iter().zip(played).enumerate().skip(1) {
        for (column, (a, b)) in a.iter().zip(b).enumerate().skip(1) {
            let (a, b): (f64, f64) = (a.parse().unwrap(), b.parse().unwrap());
            assert!((a - b).abs() <= tolerance + 1e-9, "{what}: row {row}, {}: {b} played for {a}", wanted[0][column]);
        }
    }
}

#[test]
fn fitting_a_plen2_line_gives_one_frame_and_a_too_tight_budget_names_the_tolerance_that_fits() {
    let dir = tempfile::tempdir().unwrap();
    // A knee going 0 → 450 tenths over 2 s, sampled every 20 ms (not the robot's rate).
    let line = csv("left_knee_pitch", (0..=100).map(|i| (f64::from(i) * 20.0, vec![f64::from(i) * 4.5])));
    let recording = write(dir.path(), "line.csv", &line);
    let out = dir.path().join("line.json");
    let said = fit(&recording, &out, &["--protocol", "plen2"]).unwrap();
    assert!(said.starts_with("1 frames for 2.0"), "{said}");
    assert_eq!(frames_of(&out), 1);

    // Three swings of ±40° in 3 s cannot be held by 3 frames within 1°.
    let swings = csv(
        "left_knee_pitch,right_knee_pitch",
        (0..=150).map(|i| {
            let value = 400.0 * (std::f64::consts::PI * f64::from(i) / 25.0).sin();
            (f64::from(i) * 20.0, vec![value, -value])
        }),
    );
    let recording = write(dir.path(), "swings.csv", &swings);
    let out = dir.path().join("swings.json");
    let error = fit(&recording, &out, &["--protocol", "plen2", "--max-frames", "3"]).unwrap_err();
    assert!(!out.exists(), "nothing written on failure");
    let smallest = error.split("--tolerance-deg ").nth(1).unwrap().split(". ").next().unwrap().to_string();
    assert!(error.contains("at most 3 are allowed"), "{error}");
    fit(&recording, &out, &["--protocol", "plen2", "--max-frames", "3", "--tolerance-deg", &smallest]).unwrap();
    assert!(frames_of(&out) <= 3);
    let tighter = format!("{:.1}", smallest.parse::<f64>().unwrap() - 0.1);
    assert!(fit(&recording, &out, &["--protocol", "plen2", "--max-frames", "3", "--tolerance-deg", &tighter]).is_err());

    // A PLEN2 motion holds 20 frames; a column that is no joint is named.
    let error = fit(&recording, &out, &["--protocol", "plen2", "--max-frames", "21"]).unwrap_err();
    assert!(error.contains("at most 20 frames"), "{error}");
    let wrong = write(dir.path(), "wrong.csv", "t_ms,left_knee\n0,0\n32,1\n");
    let error = fit(&wrong, &out, &["--protocol", "plen2"]).unwrap_err();
    assert!(error.contains("\"left_knee\" is not a PLEN2 joint"), "{error}");
}

#[test]
fn a_fitted_servo_recording_plays_back_within_the_tolerance() {
    let dir = tempfile::tempdir().unwrap();
    // Two servos over 3 s at 10 ms: an eased swing and a sine.
    let rows = (0..=300).map(|i| {
        let t = f64::from(i) / 300.0;
        let eased = 90.0 * (1.0 - (std::f64::consts::PI * t).cos()) / 2.0;
        (f64::from(i) * 10.0, vec![eased - 45.0, 30.0 * (2.0 * std::f64::consts::PI * t).sin()])
    });
    let recording = write(dir.path(), "wave.csv", &csv("1 shoulder,2 手肘", rows));
    let out = dir.path().join("wave.json");
    let said = fit(&recording, &out, &["--protocol", "servo", "--tolerance-deg", "0.5", "--name", "揮手"]).unwrap();
    assert!(said.contains("steps"), "{said}");
    let played = trajectory(dir.path(), &[out.to_str().unwrap(), "--macro", "1"]).unwrap();
    assert_eq!(played[0], vec!["t_ms", "1 shoulder", "2 手肘"]);
    let text = std::fs::read_to_string(&recording).unwrap();
    let input: Vec<Vec<String>> = text
        .lines()
        .skip(1)
        .map(|line| {
            let mut fields: Vec<String> = line.split(',').map(str::to_string).collect();
            fields[0] = format!("{:.0}", fields[0].parse::<f64>().unwrap());
            fields
        })
        .collect();
    // The macro plays up to its last step; every row is within 0.5°.
    assert_eq!(played.len() - 1, input.len(), "3 s at 10 ms, and the start");
    for (row, (a, b)) in input.iter().zip(&played[1..]).enumerate() {
        for column in 1..=2 {
            let (a, b): (f64, f64) = (a[column].parse().unwrap(), b[column].parse().unwrap());
            assert!((a - b).abs() <= 0.5 + 0.005, "row {row}, servo {column}: {b} played for {a}");
        }
    }
    let project: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(project["servo"]["macros"][0]["caption"], "揮手");
    let actions = project["servo"]["actions"].as_array().unwrap().len();
    assert!((4..=30).contains(&actions), "{actions} steps for an eased swing and a sine within 0.5°");
}

#[test]
fn fitting_the_official_motions_gives_them_back_within_the_tolerance_in_no_more_frames() {
    let Some(files) = official_motions() else { return };
    let dir = tempfile::tempdir().unwrap();
    assert_eq!(files.len(), 90);
    let (mut original_frames, mut fitted_frames) = (0, 0);
    for file in files {
        // One pass of its frames (a loop or a jump would play for ever).
        let (mut motion, _) = servo_studio::project::motion_json::read_motion_file(&file).unwrap();
        motion.loop_range = None;
        motion.jump_slot = None;
        let once = write(dir.path(), "once.json", &servo_studio::project::motion_json::motion_to_json(&motion));
        let slot = motion.slot.to_string();
        let wanted = trajectory(dir.path(), &[once.to_str().unwrap(), "--slot", &slot]).unwrap();
        let recording = dir.path().join("recording.csv");
        std::fs::copy(dir.path().join("out.csv"), &recording).unwrap();
        let fitted = dir.path().join("fitted.json");
        fit(&recording, &fitted, &["--protocol", "plen2"])
            .unwrap_or_else(|error| panic!("{}: {error}", file.display()));
        let played = trajectory(dir.path(), &[fitted.to_str().unwrap(), "--slot", "0"]).unwrap();
        within(&wanted, &played, 10.0, &file.display().to_string());
        let frames = frames_of(&fitted);
        assert!(frames <= motion.frames.len(), "{}: {frames} frames for {}", file.display(), motion.frames.len());
        original_frames += motion.frames.len();
        fitted_frames += frames;
    }
    eprintln!("90 official motions: {original_frames} frames, fitted within 1° in {fitted_frames}");
}

#[test]
fn a_servo_fit_that_needs_more_steps_says_steps_and_a_tolerance_to_a_tenth() {
    let dir = tempfile::tempdir().unwrap();
    // Two servos over 4 s at 10 ms: sines that 4 steps cannot hold within 1°.
    let rows = (0..=400).map(|i| {
        let t = f64::from(i) / 100.0;
        (f64::from(i) * 10.0, vec![40.0 * (1.3 * t).sin(), 25.0 * (2.1 * t + 0.4).sin()])
    });
    let recording = write(dir.path(), "sines.csv", &csv("1,2", rows));
    let out = dir.path().join("sines.json");
    let error = fit(&recording, &out, &["--protocol", "servo", "--max-frames", "4"]).unwrap_err();
    assert!(error.contains(" steps are needed to stay within 1°"), "a servo board's word is steps: {error}");
    let smallest = error.split("--tolerance-deg ").nth(1).unwrap().split(". ").next().unwrap().to_string();
    let decimals = smallest.split_once('.').map_or(0, |(_, tail)| tail.len());
    assert!(decimals <= 1, "a tolerance to 0.1°, not {smallest}");
    fit(&recording, &out, &["--protocol", "servo", "--max-frames", "4", "--tolerance-deg", &smallest]).unwrap();
    let tighter = format!("{:.1}", smallest.parse::<f64>().unwrap() - 0.1);
    assert!(fit(&recording, &out, &["--protocol", "servo", "--max-frames", "4", "--tolerance-deg", &tighter]).is_err());
}
