//! Commands never lie: a slow line is not another protocol, output that went
//! nowhere is not a success, an empty list is not "every slot", and a stand-in
//! robot holds only what a robot can.

#![cfg(unix)]
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

use servo_studio::project::{self, Family, Project, Servo, ServoProject};

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

fn run(args: &[&str]) -> (Option<i32>, String, String) {
    let (code, stdout, stderr, _) =
        common::run_in(Path::new(env!("CARGO_TARGET_TMPDIR")), args, Duration::from_secs(60));
    (code, stdout, stderr)
}

/// A servo board at 19200 baud: the 200 servos' parameters take about two
/// seconds on the line each way, past the 1 s a board may take to answer.
/// The upload times them at the line's rate and verifies; the long reply
/// still arriving is the protocol's own.
#[test]
fn a_large_project_uploads_and_verifies_at_19200_baud() {
    let dir = tempfile::tempdir().unwrap();
    let servos: Vec<Servo> = (0..200u8).map(|id| Servo::new(id, format!("關節 {id}"))).collect();
    let servo = ServoProject { project_id: 19_200, servos, ..ServoProject::default() };
    let file = dir.path().join("large.json");
    project::save(&file, &Project { family: Family::Servo, servo, ..Project::default() }).unwrap();
    let board = common::sim(&["--pty", "--baud", "19200"]);
    let (code, _, stderr) = run(&[
        "import",
        "--port",
        &board.port,
        "--baud",
        "19200",
        "--in",
        file.to_str().unwrap(),
        "--yes",
        "--no-backup",
    ]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains("verified"), "{stderr}");
    assert!(!stderr.contains("not in this protocol"), "{stderr}");
}

/// `rflex status` into /dev/null — opened for writing as a shell's
/// `>/dev/null` does, or for reading and writing as Python's
/// `subprocess.DEVNULL` and service managers hand it over — succeeds: the
/// user's choice of where the report goes. (A standard output closed before
/// the command starts, `>&-`, reaches the program as that same read-write
/// /dev/null: the runtime opens it in its place before any of the program's
/// code runs, so the two cannot be told apart, and it succeeds too.)
#[test]
fn a_report_printed_to_dev_null_read_write_or_not_is_a_success() {
    let base = common::sim(&["--protocol", "rflex", "--pty"]);
    // The command run by a shell with its stdout redirected as `redirect` says.
    let status_with = |redirect: &str| {
        let script = format!("exec \"$0\" \"$@\" {redirect}");
        let output = Command::new("sh")
            .args(["-c", &script, EXE, "rflex", "status", "--port", &base.port])
            .stdin(Stdio::null())
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        (output.status.code(), String::from_utf8_lossy(&output.stderr).into_owned())
    };
    for redirect in [">/dev/null", "<>/dev/null 1<&0", "1<>/dev/null"] {
        let (code, stderr) = status_with(redirect);
        assert_eq!(code, Some(0), "{redirect}: {stderr}");
        assert!(!stderr.contains("standard output"), "{redirect}: {stderr}");
    }
}

/// `--slots ''` or `--slots 0,,1` names no slot or an empty one: refused with
/// the accepted forms, never read as "every slot" or silently skipped.
#[test]
fn an_empty_slot_list_or_item_is_refused_with_the_accepted_forms() {
    for slots in ["", " ", "0,,1", "3,", ",5"] {
        let (code, _, stderr) =
            run(&["export", "--protocol", "plen2", "--port", "/dev/null", "--out", "x.json", "--slots", slots]);
        assert_eq!(code, Some(2), "{slots:?}: {stderr}");
        assert!(stderr.contains("e.g. 0-19,70") && stderr.contains("a range (0-19)"), "{slots:?}: {stderr}");
    }
}

/// A 21-frame motion cannot be held by a PLEN2: the emulated one refuses to
/// be preloaded with it, naming the motion, as `check` refuses the file.
#[test]
fn the_emulated_plen2_is_not_preloaded_with_what_a_plen2_cannot_hold() {
    use project::plen2::{Frame, Motion, Plen2Project, Pose};
    let dir = tempfile::tempdir().unwrap();
    let motion = Motion {
        slot: 12,
        name: "Too long".into(),
        frames: vec![Frame::new(100, Pose::default()); 21],
        loop_range: None,
        jump_slot: None,
    };
    let plen2 = Plen2Project { motions: vec![motion], ..Plen2Project::default() };
    let file = dir.path().join("too-long.json");
    project::save(&file, &Project { family: Family::Plen2, plen2, ..Project::default() }).unwrap();
    let (code, _, stderr) = run(&["check", file.to_str().unwrap()]);
    assert_eq!(code, Some(1), "check refuses it: {stderr}");
    let child = Command::new(EXE)
        .args(["sim", "--protocol", "plen2", "--pty", "--state", file.to_str().unwrap()])
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let (code, stderr) = common::ended(child, Duration::from_secs(20));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("motion 12") && stderr.contains("21 frames"), "{stderr}");
}
