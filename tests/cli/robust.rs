//! The command line where things go wrong, as a careful user meets it:
//! devices that never answer, answer garbage, drip, or speak another
//! protocol; a long transfer on a slow line; outputs that are not plain
//! files; a reader that goes away; uploads that fail half-way; and the files
//! users really write. Every command here carries a watchdog.

#![cfg(unix)]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::needless_pass_by_value)]

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use common::{Chatter, peer, run_in, sim};
use servo_studio::link::no_waker;
use servo_studio::project::{self, Action, Project, Servo, ServoProject, Step};
use servo_studio::sim::{Plen2Sim, Plen2Timing, RflexSim, RflexSimConfig, spawn_pty};

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

/// Runs `servo-studio ARGS` with a watchdog; (exit code, stdout, stderr, how long).
fn run(args: &[&str], within: Duration) -> (Option<i32>, String, String, Duration) {
    run_in(Path::new(env!("CARGO_TARGET_TMPDIR")), args, within)
}

/// `import --yes` of `file` with the backup in `dir/backups`; (exit code, stderr, the backup folder).
fn import_with_backup(port: &str, file: &Path, dir: &Path, within: Duration) -> (Option<i32>, String, PathBuf) {
    let backups = dir.join("backups");
    std::fs::create_dir(&backups).unwrap();
    let args =
        ["import", "--port", port, "--in", file.to_str().unwrap(), "--yes", "--backup-dir", backups.to_str().unwrap()];
    let (code, _, stderr, _) = run(&args, within);
    (code, stderr, backups)
}

fn motion_json(dir: &Path) -> String {
    let path = dir.join("walk.json");
    let text = r#"{"slot": 3, "name": "Walk", "codes": [], "frames": [{"transition_time_ms": 100, "outputs": [{"device": "left_knee_pitch", "value": 100}]}]}"#;
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// Every board command ends within its deadline, with the right words and
/// exit code, against peers that are silent, chatter garbage, drip a byte
/// every 500 ms, or are another family's device.
#[test]
fn every_request_ends_within_its_deadline_whatever_the_peer_does() {
    let dir = tempfile::tempdir().unwrap();
    let project = dir.path().join("project.json");
    std::fs::copy(format!("{}/tests/fixtures/project-v2.json", env!("CARGO_MANIFEST_DIR")), &project).unwrap();
    let project = project.to_str().unwrap().to_string();
    let motion = motion_json(dir.path());
    let out = dir.path().join("out.json");
    let out = out.to_str().unwrap().to_string();
    let backups = dir.path().to_str().unwrap().to_string();

    let silent = peer(Chatter::Silent);
    let garbage = peer(Chatter::Garbage);
    let drip = peer(Chatter::Drip);
    let plen2 = spawn_pty(Plen2Sim::new(Plen2Timing::default()), no_waker()).unwrap();
    let base = spawn_pty(RflexSim::new(RflexSimConfig::default()), no_waker()).unwrap();
    let servo_board = sim(&["--pty"]);

    let servo_no_answer = ["no response within", "raise it with --timeout-ms"];
    let servo_foreign = ["the device answers, but not in this protocol", "is it a servo board?", "--protocol plen2"];
    let plen2_no_answer = ["no reply within", "raise it with --timeout-ms"];
    let plen2_foreign = ["not in the PLEN2's protocol", "is it a PLEN2", "--protocol servo"];
    // (port, protocol, timeout, what it must say, the longest it should take, s: the hang guard adds 10)
    type Case<'a> = (&'a str, &'a str, Option<&'a str>, &'a [&'a str], u64);
    let cases: Vec<Case<'_>> = vec![
        (&silent.port, "servo", Some("300"), &servo_no_answer, 3),
        (&garbage.port, "servo", Some("200"), &servo_foreign, 2),
        (&drip.port, "servo", None, &servo_foreign, 3),
        (&plen2.port_name, "servo", Some("300"), &servo_no_answer, 3),
        (&base.port_name, "servo", Some("300"), &servo_no_answer, 3),
        (&silent.port, "plen2", Some("300"), &plen2_no_answer, 3),
        (&garbage.port, "plen2", None, &plen2_foreign, 3),
        (&drip.port, "plen2", None, &plen2_foreign, 3),
        (&servo_board.port, "plen2", Some("300"), &plen2_no_answer, 3),
    ];
    for (port, protocol, timeout, words, longest) in cases {
        let mut commands: Vec<Vec<&str>> = vec![
            vec!["board", "info"],
            vec!["export", "--out", &out],
            vec![
                "import",
                "--yes",
                "--backup-dir",
                &backups,
                "--in",
                if protocol == "servo" { &project } else { &motion },
            ],
        ];
        for command in &mut commands {
            command.extend(["--port", port, "--protocol", protocol]);
            if let Some(ms) = timeout {
                command.extend(["--timeout-ms", ms]);
            }
            // A generous limit tells a hang apart; how soon is the messages' to say ("within 300 ms").
            let (code, _, stderr, _) = run(command, Duration::from_secs(longest + 10));
            let case = format!("{command:?}");
            assert_eq!(code, Some(1), "{case}: {stderr}");
            for word in words {
                assert!(stderr.contains(word), "{case} must say {word:?}: {stderr}");
            }
            if let Some(ms) = timeout {
                assert!(stderr.contains(&format!("within {ms} ms")) || !stderr.contains("within"), "{case}: {stderr}");
            }
            if command[0] == "import" {
                assert!(stderr.contains("nothing was written"), "{case}: {stderr}");
            }
            assert!(!Path::new(&out).exists(), "{case}: no file is written by a failed export");
            assert!(!stderr.contains("panicked"), "{case}: {stderr}");
        }
    }
}

fn thousand_actions() -> ServoProject {
    ServoProject {
        project_id: 1000,
        servos: vec![Servo::new(1, "臂")],
        actions: (1..=1000)
            .map(|id| Action {
                id,
                caption: format!("動作{id}"),
                steps: vec![Step::new(1, i16::try_from(id % 90).unwrap(), 20)],
            })
            .collect(),
        ..ServoProject::default()
    }
}

/// A 1000-action board read and written at 115200 baud with the default
/// timeout: the action list alone is 36 KB, over three seconds on the line.
#[test]
fn a_thousand_actions_export_and_import_at_115200_baud_with_default_options() {
    let dir = tempfile::tempdir().unwrap();
    let state = dir.path().join("state.json");
    project::save(&state, &Project::servo(thousand_actions())).unwrap();
    let board = sim(&["--pty", "--baud", "115200", "--state", state.to_str().unwrap()]);
    let out = dir.path().join("export.json");
    let (code, _, stderr, _) =
        run(&["export", "--port", &board.port, "--out", out.to_str().unwrap()], Duration::from_secs(60));
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(project::load(&out).unwrap().servo.actions, thousand_actions().actions);

    let (code, stderr, _) = import_with_backup(&board.port, &out, dir.path(), Duration::from_secs(90));
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains("wrote 1003 item(s)") && stderr.contains("verified"), "{stderr}");
}

#[test]
fn export_writes_through_a_symlink_and_never_replaces_what_is_not_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let fixture = format!("{}/tests/fixtures/project-v2.json", env!("CARGO_MANIFEST_DIR"));
    let board = sim(&["--tcp", "127.0.0.1:0", "--state", &fixture]);

    // A symlink: the file it names is written, and the link stays a link.
    let target = dir.path().join("real.json");
    std::fs::write(&target, "stale").unwrap();
    let link = dir.path().join("link.json");
    std::os::unix::fs::symlink("real.json", &link).unwrap();
    let (code, _, stderr, _) =
        run(&["export", "--port", &board.port, "--out", link.to_str().unwrap()], Duration::from_secs(20));
    assert_eq!(code, Some(0), "{stderr}");
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink(), "the link is still a link");
    assert_eq!(project::load(&target).unwrap().servo.project_id, 7, "the file it points to holds the export");

    // A FIFO, a folder and a device are refused before the board is even asked.
    let fifo = dir.path().join("pipe");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let cases = [
        (fifo.to_str().unwrap().to_string(), "named pipe (FIFO)"),
        (dir.path().to_str().unwrap().to_string(), "is a folder"),
        ("/dev/full".to_string(), "a device"),
    ];
    for (path, words) in cases {
        // Refused, not blocked opening a pipe nobody reads (that would hang past the limit).
        let (code, _, stderr, _) =
            run(&["export", "--port", "tcp://127.0.0.1:9", "--out", &path], Duration::from_secs(10));
        assert_eq!(code, Some(1), "{path}: {stderr}");
        assert!(stderr.contains(words), "{path}: {stderr}");
    }
    let fifo_kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
    assert!(std::os::unix::fs::FileTypeExt::is_fifo(&fifo_kind), "the FIFO is still a FIFO");
    let full = std::fs::metadata("/dev/full").unwrap().file_type();
    assert!(std::os::unix::fs::FileTypeExt::is_char_device(&full), "/dev/full is still a device");
}

#[test]
fn board_info_into_a_reader_that_went_away_ends_quietly() {
    let fixture = format!("{}/tests/fixtures/project-v2.json", env!("CARGO_MANIFEST_DIR"));
    let board = sim(&["--tcp", "127.0.0.1:0", "--state", &fixture]);
    // `| head -0`: the reader is gone before the first line is printed.
    let (code, stderr) = common::with_stdout_closed(&["board", "info", "--port", &board.port]);
    assert!(matches!(code, Some(0 | 141)), "{code:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// An upload refused half-way names the backup, what reached the board, and
/// the command that restores it; that command does.
#[test]
fn a_failed_upload_says_what_it_left_and_how_to_restore_the_backup() {
    let dir = tempfile::tempdir().unwrap();
    let fixture = format!("{}/tests/fixtures/project-v2.json", env!("CARGO_MANIFEST_DIR"));
    let board = sim(&["--tcp", "127.0.0.1:0", "--state", &fixture, "--faults", "refuse-add=42"]);
    let before = dir.path().join("before.json");
    let (code, _, stderr, _) =
        run(&["export", "--port", &board.port, "--out", before.to_str().unwrap()], Duration::from_secs(20));
    assert_eq!(code, Some(0), "{stderr}");

    let mut next = common::rich_project();
    next.project_id = 77;
    let next_path = dir.path().join("next.json");
    project::save(&next_path, &Project::servo(next)).unwrap();
    let (code, stderr, backups) = import_with_backup(&board.port, &next_path, dir.path(), Duration::from_secs(30));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("action 42 \"揮手\": the board refused it"), "{stderr}");
    assert!(stderr.contains("the device may now be half written: 4 of 11 items reached it"), "{stderr}");
    let backup = std::fs::read_dir(&backups).unwrap().next().unwrap().unwrap().path();
    assert!(stderr.contains(&format!("saved in {}", backup.display())), "{stderr}");
    let restore_line =
        stderr.lines().find(|line| line.contains("to put it back as it was:")).expect("a restore command");
    let restore: Vec<&str> = restore_line.split_once(": servo-studio ").unwrap().1.split(' ').collect();
    assert_eq!(restore, ["import", "--port", &board.port, "--in", backup.to_str().unwrap(), "--force", "--yes"]);

    // The advice works: the board holds what it held (its own backup goes where it runs).
    let (code, _, stderr, _) = run_in(dir.path(), &restore, Duration::from_secs(30));
    assert_eq!(code, Some(0), "{stderr}");
    let after = dir.path().join("after.json");
    let (code, _, stderr, _) =
        run(&["export", "--port", &board.port, "--out", after.to_str().unwrap()], Duration::from_secs(20));
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(project::load(&after).unwrap(), project::load(&before).unwrap());
}

#[test]
fn an_upload_that_fails_before_writing_says_nothing_was_written() {
    let dir = tempfile::tempdir().unwrap();
    let fixture = format!("{}/tests/fixtures/project-v2.json", env!("CARGO_MANIFEST_DIR"));
    // The link drops while the board is being backed up (its fifth answer).
    let board = sim(&["--tcp", "127.0.0.1:0", "--state", &fixture, "--faults", "disconnect-after=5"]);
    let (code, _, stderr, _) = run(
        &["import", "--port", &board.port, "--in", &fixture, "--yes", "--backup-dir", dir.path().to_str().unwrap()],
        Duration::from_secs(20),
    );
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("while backing the device up"), "{stderr}");
    assert!(stderr.contains("nothing was written"), "{stderr}");
    assert!(!stderr.contains("to put it back"), "nothing to restore: {stderr}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "no half backup");
}

#[test]
fn check_reads_what_users_really_write_and_names_what_is_wrong() {
    let dir = tempfile::tempdir().unwrap();
    let fixture =
        std::fs::read_to_string(format!("{}/tests/fixtures/project-v2.json", env!("CARGO_MANIFEST_DIR"))).unwrap();

    // A byte-order mark (Notepad) and a misspelt key.
    let bom = dir.path().join("bom.json");
    std::fs::write(&bom, format!("\u{feff}{}", fixture.replacen("\"min_deg\"", "\"min_degs\"", 1))).unwrap();
    let (code, stdout, stderr, _) = run(&["check", bom.to_str().unwrap()], Duration::from_secs(10));
    assert_eq!(code, Some(0), "warnings only: {stdout}{stderr}");
    assert!(stdout.contains("warning: servo.servos[0].min_degs: unknown key, ignored"), "{stdout}");
    assert!(stdout.ends_with("0 error(s), 1 warning(s)\n"), "{stdout}");

    // A folder of motions: one fine, one unreadable, one with a value out of
    // range, one with a joint twice, one with an unknown code.
    let motions = dir.path().join("motions");
    std::fs::create_dir(&motions).unwrap();
    let frame = |outputs: &str| format!(r#"{{"transition_time_ms": 100, "outputs": [{outputs}]}}"#);
    let motion = |slot: u8, name: &str, frames: &[String], codes: &str| {
        format!(r#"{{"slot": {slot}, "name": "{name}", "codes": [{codes}], "frames": [{}]}}"#, frames.join(", "))
    };
    let knee = |value: i32| format!(r#"{{"device": "left_knee_pitch", "value": {value}}}"#);
    std::fs::write(motions.join("00_fine.json"), motion(0, "Fine", &[frame(&knee(100))], "")).unwrap();
    std::fs::write(motions.join("01_broken.json"), "{\"slot\": 1, \"frames\": [").unwrap();
    std::fs::write(motions.join("02_far.json"), motion(2, "Far", &[frame(&knee(0)), frame(&knee(5000))], "")).unwrap();
    let twice = format!("{}, {}", knee(1), knee(2));
    std::fs::write(motions.join("03_twice.json"), motion(3, "Twice", &[frame(&twice)], "")).unwrap();
    let explode = r#"{"method": "explode", "arguments": []}"#;
    std::fs::write(motions.join("04_code.json"), motion(4, "Code", &[frame(&knee(0))], explode)).unwrap();
    std::fs::write(motions.join("05_huge.json"), motion(5, "Huge", &[frame(&knee(99_999))], "")).unwrap();
    let (code, stdout, stderr, _) = run(&["check", motions.to_str().unwrap()], Duration::from_secs(10));
    assert_eq!(code, Some(1), "{stdout}{stderr}");
    assert!(stdout.contains("01_broken.json: not a PLEN2 motion.json"), "{stdout}");
    assert!(
        stdout.contains("error: 02_far.json: motion 2 \"Far\", frame 2: left_knee_pitch 5000 is outside -1800..=1800"),
        "{stdout}"
    );
    assert!(
        stdout.contains("03_twice.json: not a PLEN2 motion.json: frame 1: left_knee_pitch is listed twice"),
        "{stdout}"
    );
    assert!(stdout.contains("04_code.json: not a PLEN2 motion.json: codes[0]: unknown code \"explode\""), "{stdout}");
    assert!(
        stdout.contains("05_huge.json: not a PLEN2 motion.json: frame 1, left_knee_pitch: value 99999 is out of range"),
        "{stdout}"
    );
    assert!(stdout.contains("5 error(s)"), "every file checked, the good one too: {stdout}");
    assert!(!stdout.contains("00_fine.json"), "{stdout}");

    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    let (code, _, stderr, _) = run(&["check", empty.to_str().unwrap()], Duration::from_secs(10));
    assert_eq!(code, Some(1));
    assert!(stderr.contains("holds no motion.json (*.json) files"), "{stderr}");

    // A folder given to import: said once, not "cannot read X: cannot read X".
    let (code, _, stderr, _) =
        run(&["import", "--port", "/dev/null", "--in", empty.to_str().unwrap(), "--yes"], Duration::from_secs(10));
    assert_eq!(code, Some(1));
    assert_eq!(stderr.matches(empty.to_str().unwrap()).count(), 1, "{stderr}");
}

/// `check` of a 200 MB project stays under 1 GB (it read the whole text into
/// a JSON tree first, at 8× the file's size).
#[test]
fn checking_a_200_mb_project_stays_under_1_gb() {
    let dir = tempfile::tempdir().unwrap();
    let servos: Vec<Servo> = (0..64u8).map(|id| Servo::new(id, format!("關節{id}"))).collect();
    let actions: Vec<Action> = (1..=32_000)
        .map(|id| Action {
            id,
            caption: format!("動作{id}"),
            steps: (0..64u8).map(|servo_id| Step::new(servo_id, i16::try_from(id % 90).unwrap(), 50)).collect(),
        })
        .collect();
    let path = dir.path().join("huge.json");
    project::save(&path, &Project::servo(ServoProject { project_id: 1, servos, actions, ..ServoProject::default() }))
        .unwrap();
    let size = std::fs::metadata(&path).unwrap().len();
    assert!(size > 200_000_000, "{size} bytes");
    // An address-space cap of 1 GiB: more than that and the check dies.
    let script = format!("ulimit -v 1048576 && exec {EXE} check {}", path.display());
    let output = Command::new("sh").args(["-c", &script]).output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{stdout}{}", String::from_utf8_lossy(&output.stderr));
    assert!(stdout.ends_with("0 error(s), 0 warning(s)\n"), "{stdout}");
}
