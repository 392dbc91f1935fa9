//! The command line against an adversary: numbers far out of range, signals
//! in the middle of a write to a board, a client killed mid-drive, outputs
//! that cannot be written, inputs that are not files, and files built to
//! exhaust memory. Every command carries a watchdog; no test waits on a
//! clock to synchronise (signals are sent when the emulated board reports
//! the write they interrupt).

#![cfg(unix)]
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

use common::{Chatter, ended, peer, spawn_quiet};
use servo_studio::link::{LinkEvent, no_waker};
use servo_studio::project::{self, Command as MacroCommand, Macro, Project, Run};
use servo_studio::protocol::plen2::Command as Plen2Command;
use servo_studio::protocol::rflex::Command as RflexCommand;
use servo_studio::protocol::servo::Message;
use servo_studio::sim::{
    Plen2Sim, Plen2SimEvent, Plen2Timing, RflexSim, RflexSimConfig, RflexSimEvent, ServoSim, SimConfig, SimEvent,
    spawn_pty, spawn_tcp,
};

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

/// Runs `servo-studio ARGS` in `cwd` with a watchdog; (exit code, stdout, stderr).
fn run_in(cwd: &Path, args: &[&str], within: Duration) -> (Option<i32>, String, String) {
    let (code, stdout, stderr, _) = common::run_in(cwd, args, within);
    (code, stdout, stderr)
}

fn run(args: &[&str]) -> (Option<i32>, String, String) {
    run_in(Path::new(env!("CARGO_TARGET_TMPDIR")), args, Duration::from_secs(20))
}

fn signal(pid: u32, name: &str) {
    assert!(Command::new("kill").args([&format!("-{name}"), &pid.to_string()]).status().unwrap().success());
}

/// Every number a user types is bounded while the command line is read:
/// refused (status 2, with the bounds) before a port is opened.
#[test]
fn numbers_out_of_their_bounds_are_refused_before_anything_is_opened() {
    let nowhere = "/dev/does-not-exist-servo";
    let cases: &[(&[&str], &str)] = &[
        (&["rflex", "drive", "--port", nowhere, "--speed", "0.3", "--seconds", "1e20"], "outside 0..=3600 s"),
        (&["rflex", "drive", "--port", nowhere, "--speed", "0.3", "--seconds", "1.8e19"], "outside 0..=3600 s"),
        (&["rflex", "drive", "--port", nowhere, "--speed", "0.3", "--seconds", "NaN"], "not a finite number"),
        (&["rflex", "drive", "--port", nowhere, "--speed", "1e300", "--seconds", "1"], "outside -10..=10 m/s"),
        (&["rflex", "drive", "--port", nowhere, "--speed", "0", "--accel", "0", "--seconds", "1"], "above 0"),
        (&["rflex", "drive", "--port", nowhere, "--speed", "0", "--turn", "-inf", "--seconds", "1"], "finite"),
        (&["board", "info", "--port", nowhere, "--timeout-ms", "0"], "outside 1..=600000 ms"),
        (&["board", "info", "--port", nowhere, "--baud", "0"], "outside 300..=4000000 baud"),
        (&["sim", "--baud", "0"], "outside 300..=4000000 baud"),
        (&["sim", "--memory", "-1"], "outside 0..=1073741824 bytes"),
        (&["sim", "--turnaround-ms", "99999999999"], "outside 0..=60000 ms"),
        (&["trajectory", "x.json", "--macro", "1", "--seconds", "1e12", "--out", "x.csv"], "outside 0..=3600 s"),
        (&["trajectory", "x.json", "--slot", "90", "--out", "x.csv"], "outside 0..=89"),
    ];
    for (args, words) in cases {
        let (code, _, stderr) = run(args);
        assert_eq!(code, Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(words), "{args:?} must say {words:?}: {stderr}");
        assert!(!stderr.contains("panicked") && !stderr.contains("not found"), "{args:?}: {stderr}");
    }
}

/// Options that do not apply to what they were given to are refused, never ignored.
#[test]
fn options_that_do_not_apply_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let fixture = format!("{}/tests/fixtures/project-v2.json", env!("CARGO_MANIFEST_DIR"));
    let cases: &[(&[&str], &str)] = &[
        (&["sim", "--protocol", "rflex", "--state", &fixture], "--state do(es) not apply to the emulated rflex board"),
        (&["sim", "--protocol", "plen2", "--baud", "9600"], "--baud do(es) not apply"),
        (&["sim", "--protocol", "servo", "--robot", "magellan"], "--robot do(es) not apply"),
        (&["rflex", "status", "--port", "tcp://127.0.0.1:9", "--protocol", "servo"], "--protocol servo does not apply"),
        (&["board", "info", "--port", "tcp://127.0.0.1:9", "--pacing", "safe"], "--pacing is for PLEN2"),
    ];
    for (args, words) in cases {
        let (code, stdout, stderr) = run(args);
        assert_eq!(code, Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains(words), "{args:?} must say {words:?}: {stderr}");
        assert!(stdout.is_empty(), "nothing started: {stdout}");
    }

    // A read-only file is replaced only with --force.
    let board = common::sim(&["--tcp", "127.0.0.1:0", "--state", &fixture]);
    let out = dir.path().join("kept.json");
    std::fs::write(&out, "precious").unwrap();
    let mut permissions = std::fs::metadata(&out).unwrap().permissions();
    permissions.set_readonly(true);
    std::fs::set_permissions(&out, permissions).unwrap();
    let (code, _, stderr) = run(&["export", "--port", &board.port, "--out", out.to_str().unwrap()]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("is read-only") && stderr.contains("--force"), "{stderr}");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "precious");
    let (code, _, stderr) = run(&["export", "--port", &board.port, "--out", out.to_str().unwrap(), "--force"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(project::load(&out).unwrap().servo.project_id, 7);
    assert!(std::fs::metadata(&out).unwrap().permissions().readonly(), "it stays read-only");
}

/// Waits for the first event `wanted` picks out of an emulator's events.
fn wait_for<E: std::fmt::Debug>(events: &crossbeam_channel::Receiver<LinkEvent<E>>, wanted: impl Fn(&E) -> bool) {
    let deadline = std::time::Instant::now() + Duration::from_secs(30);
    loop {
        let left = deadline.saturating_duration_since(std::time::Instant::now());
        match events.recv_timeout(left) {
            Ok(LinkEvent::Driver(event)) if wanted(&event) => return,
            Ok(_) => {}
            Err(error) => panic!("the awaited event never came: {error}"),
        }
    }
}

/// The restore command a stopped upload printed, as arguments.
fn restore_command(stderr: &str) -> Vec<String> {
    let line = stderr.lines().find(|line| line.contains("to put it back as it was:")).expect("a restore command");
    line.split_once(": servo-studio ").unwrap().1.split(' ').map(str::to_string).collect()
}

/// SIGINT and SIGTERM in the middle of a servo import: it stops between two
/// packets, says what reached the board, where the backup is and how to
/// restore it, exits 130 / 143; the command it prints puts the board back.
#[test]
fn a_signal_mid_import_stops_between_packets_and_the_printed_command_restores_the_board() {
    for (name, status) in [("INT", 130), ("TERM", 143)] {
        let dir = tempfile::tempdir().unwrap();
        let before = common::exported(common::rich_project());
        let image = servo_studio::device::servo::ServoImage::from_project(&before).unwrap();
        // 19200 baud: the upload takes long enough to be caught in the middle.
        let config = SimConfig { baud: Some(19_200), ..SimConfig::default() };
        let board = spawn_pty(ServoSim::new(config, image), no_waker()).unwrap();

        let mut next = common::rich_project();
        next.project_id = 99;
        let next_path = dir.path().join("next.json");
        project::save(&next_path, &Project::servo(next)).unwrap();
        let backups = dir.path().join("backups");
        std::fs::create_dir(&backups).unwrap();
        let (next_path, backups) = (next_path.to_str().unwrap(), backups.to_str().unwrap());
        let child =
            spawn_quiet(&["import", "--port", &board.port_name, "--in", next_path, "--yes", "--backup-dir", backups]);
        // The backup is taken and the board cleared: the first item is being written.
        wait_for(board.events(), |event| matches!(event, SimEvent::Handled(Message::AddActionRequest(_))));
        signal(child.id(), name);
        let (code, stderr) = ended(child, Duration::from_secs(30));
        assert_eq!(code, Some(status), "SIG{name}: {stderr}");
        assert!(stderr.contains(&format!("interrupted by SIG{name}")), "{stderr}");
        assert!(stderr.contains("the device may now be half written"), "what reached it is said: {stderr}");
        let backup = std::fs::read_dir(backups).unwrap().next().unwrap().unwrap().path();
        assert!(stderr.contains(&backup.display().to_string()), "{stderr}");

        let restore = restore_command(&stderr);
        let restore: Vec<&str> = restore.iter().map(String::as_str).collect();
        let (code, _, stderr) = run_in(dir.path(), &restore, Duration::from_secs(60));
        assert_eq!(code, Some(0), "the restore command works: {stderr}");
        let after = dir.path().join("after.json");
        let (code, _, stderr) = run_in(
            dir.path(),
            &["export", "--port", &board.port_name, "--out", after.to_str().unwrap()],
            Duration::from_secs(60),
        );
        assert_eq!(code, Some(0), "{stderr}");
        assert_eq!(project::load(&after).unwrap().servo, before, "SIG{name}: the board holds what it held");
    }
}

/// SIGINT in the middle of a PLEN2 import says the same, with the PLEN2's
/// restore command; an export to a file stopped by a signal leaves no file.
#[test]
fn a_signal_mid_plen2_import_or_mid_export_leaves_nothing_unsaid_and_no_partial_file() {
    let dir = tempfile::tempdir().unwrap();
    let robot = spawn_pty(Plen2Sim::new(Plen2Timing::default()), no_waker()).unwrap();
    let motion = r#"{"slot": 3, "name": "Walk", "codes": [], "frames": [{"transition_time_ms": 100, "outputs": [{"device": "left_knee_pitch", "value": 100}]}]}"#;
    let motions = dir.path().join("motions");
    std::fs::create_dir(&motions).unwrap();
    for slot in 0..30 {
        std::fs::write(
            motions.join(format!("{slot:02}.json")),
            motion.replace("\"slot\": 3", &format!("\"slot\": {slot}")),
        )
        .unwrap();
    }
    let backups = dir.path().join("backups");
    std::fs::create_dir(&backups).unwrap();
    let (motions, backups) = (motions.to_str().unwrap(), backups.to_str().unwrap());
    let child = spawn_quiet(&[
        "import",
        "--port",
        &robot.port_name,
        "--protocol",
        "plen2",
        "--in",
        motions,
        "--yes",
        "--backup-dir",
        backups,
    ]);
    // A motion header stored: the upload is under way.
    wait_for(robot.events(), |event| matches!(event, Plen2SimEvent::Executed(Plen2Command::Header(_))));
    signal(child.id(), "INT");
    let (code, stderr) = ended(child, Duration::from_secs(60));
    assert_eq!(code, Some(130), "{stderr}");
    assert!(stderr.contains("interrupted by SIGINT"), "{stderr}");
    assert!(stderr.contains("to put it back as it was: servo-studio import --protocol plen2"), "{stderr}");

    // An export stopped by a signal: no file, no temporary file.
    let fixture = format!("{}/tests/fixtures/project-v2.json", env!("CARGO_MANIFEST_DIR"));
    let image =
        servo_studio::device::servo::ServoImage::from_project(&project::load(Path::new(&fixture)).unwrap().servo)
            .unwrap();
    let config = SimConfig { baud: Some(9_600), ..SimConfig::default() };
    let board = spawn_pty(ServoSim::new(config, image), no_waker()).unwrap();
    let out_dir = dir.path().join("out");
    std::fs::create_dir(&out_dir).unwrap();
    let out = out_dir.join("board.json");
    let child = spawn_quiet(&["export", "--port", &board.port_name, "--out", out.to_str().unwrap()]);
    wait_for(board.events(), |event| matches!(event, SimEvent::Handled(Message::QueryActionListRequest)));
    signal(child.id(), "TERM");
    let (code, stderr) = ended(child, Duration::from_secs(30));
    assert_eq!(code, Some(143), "{stderr}");
    assert!(stderr.contains("interrupted by SIGTERM") && stderr.contains("was not written"), "{stderr}");
    assert_eq!(std::fs::read_dir(&out_dir).unwrap().count(), 0, "no file and no temporary file");
}

/// A client killed mid-drive over TCP: the emulated base stops by its own
/// dead-man, as a real base would, with no client connected.
#[test]
fn a_client_killed_mid_drive_leaves_a_base_that_stops_by_its_dead_man() {
    let base = spawn_tcp(RflexSim::new(RflexSimConfig::default()), "127.0.0.1:0".parse().unwrap(), no_waker()).unwrap();
    let mut child = Command::new(EXE)
        .args(["rflex", "drive", "--port", &base.port_name, "--speed", "0.3", "--seconds", "60"])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Driving: a velocity command with a speed arrived.
    wait_for(
        base.events(),
        |event| matches!(event, RflexSimEvent::Received(RflexCommand::AxisSetDir { axis: 0, speed, .. }) if *speed > 0),
    );
    child.kill().unwrap();
    child.wait().unwrap();
    wait_for(base.events(), |event| matches!(event, RflexSimEvent::DeadManStop));
}

/// A response that begins and then drips is a slow line, not another protocol.
#[test]
fn a_response_that_begins_and_drips_is_called_a_slow_line() {
    let device = peer(Chatter::Begins);
    let (code, _, stderr) = run(&["board", "info", "--port", &device.port, "--timeout-ms", "300"]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("the response began but did not arrive whole"), "{stderr}");
    assert!(!stderr.contains("not in this protocol"), "{stderr}");
}

/// Output that cannot be written is never a silent success; stderr that
/// cannot be written never panics.
#[test]
fn output_that_cannot_be_written_is_never_a_silent_success() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.json");
    let fixture =
        std::fs::read_to_string(format!("{}/tests/fixtures/project-v2.json", env!("CARGO_MANIFEST_DIR"))).unwrap();
    std::fs::write(&bad, fixture.replacen("\"min_deg\": -90", "\"min_deg\": 500", 1)).unwrap();
    let good = dir.path().join("good.json");
    std::fs::write(&good, &fixture).unwrap();

    // `check | head -0`: the reader is gone before the first line; the result stands.
    for (file, status) in [(&bad, 1), (&good, 0)] {
        let (code, stderr) = common::with_stdout_closed(&["check", file.to_str().unwrap()]);
        assert_eq!(code, Some(status), "{}: {stderr}", file.display());
    }
    // `> /dev/full`: a quiet message, status 1.
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
    let child =
        Command::new(EXE).args(["check", good.to_str().unwrap()]).stdout(full).stderr(Stdio::piped()).spawn().unwrap();
    let (code, stderr) = ended(child, Duration::from_secs(20));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("cannot write the output") && !stderr.contains("panicked"), "{stderr}");
    // `2> /dev/full`: the error is lost, the status is still the truth.
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
    let mut child = Command::new(EXE)
        .args(["board", "info", "--port", "/dev/does-not-exist-servo"])
        .stdout(Stdio::null())
        .stderr(full)
        .spawn()
        .unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(1), "not a panic (101)");
}

/// Inputs that are not regular files are refused at once, named; a folder
/// check says every entry it skipped and why.
#[test]
fn inputs_that_are_not_files_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.json");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let fifo = fifo.to_str().unwrap();
    let out = dir.path().join("out.csv");
    let out = out.to_str().unwrap();
    let cases: &[&[&str]] = &[
        &["check", fifo],
        &["check", "/dev/zero"],
        &["trajectory", fifo, "--action", "1", "--out", out],
        &["import", "--port", "/dev/does-not-exist-servo", "--in", fifo, "--yes"],
        &["sim", "--state", fifo],
        &["sim", "--protocol", "plen2", "--state", fifo],
        &["gui", fifo],
    ];
    for args in cases {
        let (code, stdout, stderr) = run(args);
        assert_eq!(code, Some(1), "{args:?}: {stdout}{stderr}");
        assert!(stderr.contains("not a file: it is not read"), "{args:?}: {stderr}");
        assert!(stderr.contains("named pipe (FIFO)") || stderr.contains("a device"), "{args:?}: {stderr}");
    }

    // A folder: a dangling link, a link loop, a FIFO and a note are each said;
    // a project file in it is checked as a project, not as a motion.json.
    let folder = dir.path().join("motions");
    std::fs::create_dir(&folder).unwrap();
    std::os::unix::fs::symlink("gone.json", folder.join("dangling.json")).unwrap();
    std::os::unix::fs::symlink("loop.json", folder.join("loop.json")).unwrap();
    assert!(Command::new("mkfifo").arg(folder.join("pipe.json")).status().unwrap().success());
    std::fs::write(folder.join("README.txt"), "notes").unwrap();
    std::fs::copy(format!("{}/tests/fixtures/project-v2.json", env!("CARGO_MANIFEST_DIR")), folder.join("robot.json"))
        .unwrap();
    let (code, stdout, stderr) = run(&["check", folder.to_str().unwrap()]);
    assert_eq!(code, Some(1), "{stdout}{stderr}");
    for words in ["dangling.json", "loop.json", "pipe.json", "README.txt"] {
        assert!(stdout.contains(words), "{words} is said: {stdout}");
    }
    assert!(!stdout.contains("robot.json: not a PLEN2 motion.json"), "{stdout}");
    assert!(stdout.contains("3 error(s)"), "three unreadable .json entries: {stdout}");
}

/// The messages a user meets, each saying what is true in few words.
#[test]
fn messages_say_what_is_true() {
    let dir = tempfile::tempdir().unwrap();
    let array = dir.path().join("array.json");
    std::fs::write(&array, "[1, 2]").unwrap();
    let (code, stdout, stderr) = run(&["check", array.to_str().unwrap()]);
    assert_eq!(code, Some(1));
    assert!(stderr.contains("a JSON array") && !stderr.contains("expected a string"), "{stdout}{stderr}");

    let project_file = dir.path().join("p.json");
    std::fs::copy(format!("{}/tests/fixtures/project-v2.json", env!("CARGO_MANIFEST_DIR")), &project_file).unwrap();
    let (code, _, stderr) = run(&["board", "info", "--port", project_file.to_str().unwrap()]);
    assert_eq!(code, Some(1));
    assert!(stderr.contains("is a regular file, not a serial port") && !stderr.contains("typewriter"), "{stderr}");
    let (_, _, stderr) = run(&["board", "info", "--port", "/dev/null"]);
    assert!(stderr.contains("not a serial port") && !stderr.contains("typewriter"), "{stderr}");

    // A caption of 100,000 characters is not echoed whole.
    let mut servo = project::load(&project_file).unwrap().servo;
    servo.actions[0].caption = "揮".repeat(100_000);
    let long = dir.path().join("long.json");
    project::save(&long, &Project::servo(servo)).unwrap();
    let (code, stdout, _) = run(&["check", long.to_str().unwrap()]);
    assert_eq!(code, Some(1));
    assert!(stdout.lines().all(|line| line.chars().count() < 300), "{}", &stdout[..stdout.len().min(600)]);
    assert!(stdout.contains("…"), "{stdout}");

    // No display: said without a path from the build machine.
    let output = Command::new(EXE)
        .arg("gui")
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("DISPLAY") && !stderr.contains(".cargo") && !stderr.contains(".rs:"), "{stderr}");

    // A file that could not be written where none was: no "previous file".
    let (code, _, stderr) =
        run(&["trajectory", project_file.to_str().unwrap(), "--action", "1", "--out", "/does-not-exist/t.csv"]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(!stderr.contains("previous file"), "{stderr}");
}

fn looped(run: Run, loop_count: i16) -> MacroCommand {
    MacroCommand { run, ratio_percent: 100, loop_count, stored_total_ms: None }
}

/// `trajectory` refuses what it cannot trace (cycles, named; a motion the
/// robot cannot store) and caps its work, writing nothing then.
#[test]
fn trajectory_refuses_what_it_cannot_play_and_caps_its_work() {
    let dir = tempfile::tempdir().unwrap();
    let mut servo = common::rich_project();
    let macro_of = |id: i32, commands: Vec<MacroCommand>| Macro { id, caption: String::new(), commands };
    servo.macros.push(macro_of(500, vec![looped(Run::Macro { macro_id: 500 }, 1)]));
    servo.macros.push(macro_of(501, vec![looped(Run::Macro { macro_id: 502 }, 1)]));
    servo.macros.push(macro_of(502, vec![looped(Run::Macro { macro_id: 501 }, 1)]));
    servo.macros.push(macro_of(510, vec![looped(Run::Delay { delay_ms: 0 }, 32_767)]));
    servo.macros.push(macro_of(511, vec![looped(Run::Macro { macro_id: 510 }, 32_767)]));
    servo.macros.push(macro_of(512, vec![looped(Run::Macro { macro_id: 511 }, 32_767)]));
    let file = dir.path().join("macros.json");
    project::save(&file, &Project::servo(servo)).unwrap();
    let file = file.to_str().unwrap();
    let out = dir.path().join("t.csv");
    let out_text = out.to_str().unwrap();
    let cases: &[(&str, &str)] = &[
        ("500", "macro 500 never ends: it runs itself again (macro 500 → macro 500)"),
        ("501", "macro 501 never ends: it runs itself again (macro 501 → macro 502 → macro 501)"),
        ("512", "more than 4000000 steps and loop turns"),
    ];
    for (id, words) in cases {
        let (code, _, stderr) = run(&["trajectory", file, "--macro", id, "--out", out_text]);
        assert_eq!(code, Some(1), "{id}: {stderr}");
        assert!(stderr.contains(words), "{id}: {stderr}");
        assert!(!out.exists(), "{id}: nothing written");
    }

    // An hour of 200 servos is 72 million values: refused, with what would fit.
    let mut wide = common::rich_project();
    wide.servos = (1..=200).map(|id| project::Servo::new(id, format!("s{id}"))).collect();
    wide.macros.push(macro_of(600, vec![looped(Run::Delay { delay_ms: 4_000_000 }, 1)]));
    let wide_path = dir.path().join("wide.json");
    project::save(&wide_path, &Project::servo(wide)).unwrap();
    let (code, _, stderr) =
        run(&["trajectory", wide_path.to_str().unwrap(), "--macro", "600", "--seconds", "3600", "--out", out_text]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("360002 rows × 201 columns") && stderr.contains("at most --seconds 2487"), "{stderr}");
    assert!(!out.exists());

    // A PLEN2 motion of 21 frames cannot be stored, so cannot be played.
    let frame = r#"{"transition_time_ms": 100, "outputs": [{"device": "left_knee_pitch", "value": 100}]}"#;
    let frames = vec![frame; 21].join(", ");
    let motion = dir.path().join("long.json");
    std::fs::write(&motion, format!(r#"{{"slot": 4, "name": "Long", "codes": [], "frames": [{frames}]}}"#)).unwrap();
    let motion = motion.to_str().unwrap();
    let (code, _, stderr) = run(&["trajectory", motion, "--slot", "4", "--out", out_text]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("21 frames") && stderr.contains("cannot be played"), "{stderr}");
    assert!(!out.exists());
    // … and is refused by check and by import, even forced, before a byte is sent.
    let (code, stdout, _) = run(&["check", motion]);
    assert_eq!(code, Some(1));
    assert!(stdout.contains("Long") && stdout.contains("21"), "{stdout}");
    let robot = spawn_pty(Plen2Sim::new(Plen2Timing::default()), no_waker()).unwrap();
    let (code, _, stderr) = run_in(
        dir.path(),
        &["import", "--port", &robot.port_name, "--protocol", "plen2", "--in", motion, "--force", "--yes"],
        Duration::from_secs(10),
    );
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("21 frames") && stderr.contains("nothing was written"), "{stderr}");
    // A barrier: `board info` reads the robot through the same line, after
    // anything the refused import could have sent; the first thing the robot
    // runs is its `<VI`.
    let (code, _, stderr) = run(&["board", "info", "--protocol", "plen2", "--port", &robot.port_name]);
    assert_eq!(code, Some(0), "{stderr}");
    let executed: Vec<Plen2Command> = robot
        .events()
        .try_iter()
        .filter_map(|event| match event {
            LinkEvent::Driver(Plen2SimEvent::Executed(command)) => Some(command),
            _ => None,
        })
        .collect();
    assert_eq!(executed.first().map(Plen2Command::code), Some("<VI"), "nothing before the barrier: {executed:?}");
}

/// A file of 9 million entries, each with an unknown key (about 150 MB), is
/// checked in bounded memory: refused where its list outgrows what a board
/// counts; and 3.5 million unknown keys in one place are counted, not kept.
#[test]
fn hostile_files_are_checked_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("entries.json");
    {
        let mut file = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
        write!(file, r#"{{"format": "servo-studio-project", "version": 2, "family": "servo", "servo": {{"servos": ["#)
            .unwrap();
        for id in 0..9_000_000u32 {
            let comma = if id == 0 { "" } else { "," };
            write!(file, r#"{comma}{{"id":{},"x":1}}"#, id % 200).unwrap();
        }
        write!(file, "]}}}}").unwrap();
    }
    let size = std::fs::metadata(&path).unwrap().len();
    assert!(size > 140_000_000, "{size} bytes");
    let script = format!("ulimit -v 1048576 && exec {EXE} check {}", path.display());
    let output = Command::new("sh").args(["-c", &script]).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("more than 32767 entries"), "{stderr}");

    let keys = dir.path().join("keys.json");
    {
        let mut file = std::io::BufWriter::new(std::fs::File::create(&keys).unwrap());
        write!(file, r#"{{"format": "servo-studio-project", "version": 2, "family": "servo", "servo": {{"#).unwrap();
        for key in 0..3_500_000u32 {
            write!(file, r#""k{key}":0,"#).unwrap();
        }
        write!(file, r#""project_id": 1}}}}"#).unwrap();
    }
    let script = format!("ulimit -v 1048576 && exec {EXE} check {}", keys.display());
    let output = Command::new("sh").args(["-c", &script]).output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(stdout.ends_with("0 error(s), 3500000 warning(s)\n"), "{}", &stdout[stdout.len().saturating_sub(300)..]);
    assert!(stdout.lines().count() < 1100, "the first thousand listed, the rest counted");
}
