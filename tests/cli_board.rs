//! The board commands of `servo-studio`, run as a user runs them, against
//! `servo-studio sim` in another process.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::needless_pass_by_value)]

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Output, Stdio};
use std::time::Duration;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

fn fixture() -> String {
    format!("{}/tests/fixtures/project-v1.json", env!("CARGO_MANIFEST_DIR"))
}

/// A `servo-studio sim` process, killed when dropped.
struct Sim {
    child: Child,
    port: String,
}

impl Drop for Sim {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn sim(args: &[&str]) -> Sim {
    let mut child =
        Command::new(EXE).arg("sim").args(args).stdout(Stdio::piped()).stderr(Stdio::null()).spawn().unwrap();
    let stdout = child.stdout.take().unwrap();
    let (line_tx, line_rx) = crossbeam_channel::bounded(1);
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = line_tx.send(line);
    });
    let port = line_rx.recv_timeout(Duration::from_secs(30)).expect("the sim printed its port").trim().to_string();
    assert!(!port.is_empty(), "sim printed no port");
    Sim { child, port }
}

fn run(args: &[&str]) -> Output {
    Command::new(EXE).args(args).stdin(Stdio::null()).output().unwrap()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// The board-carried parts of a project file (client-side limits aside).
fn board_view(path: &Path) -> servo_studio::device::board::BoardImage {
    servo_studio::device::board::BoardImage::from_project(&servo_studio::project::load(path).unwrap()).unwrap()
}

#[test]
fn sim_on_tcp_then_info_export_and_import() {
    let sim = sim(&["--tcp", "127.0.0.1:0", "--state", &fixture()]);
    assert!(sim.port.starts_with("tcp://127.0.0.1:"), "{}", sim.port);
    let dir = tempfile::tempdir().unwrap();

    let info = run(&["board", "info", "--port", &sim.port]);
    assert!(info.status.success(), "{}", stderr(&info));
    let printed = String::from_utf8_lossy(&info.stdout);
    assert!(printed.contains("project id: 20261121"), "{printed}");
    assert!(printed.contains("battery: 870‰"), "{printed}");

    let out = dir.path().join("exported.json");
    let export = run(&["export", "--port", &sim.port, "--out", out.to_str().unwrap()]);
    assert!(export.status.success(), "{}", stderr(&export));
    assert_eq!(board_view(&out), board_view(Path::new(&fixture())));

    // Without --yes and without a terminal, import refuses and changes nothing.
    let refused = run(&["import", "--port", &sim.port, "--in", &fixture()]);
    assert_eq!(refused.status.code(), Some(1));
    assert!(stderr(&refused).contains("pass --yes"), "{}", stderr(&refused));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);

    let backups = dir.path().join("backups");
    std::fs::create_dir(&backups).unwrap();
    let import =
        run(&["import", "--port", &sim.port, "--in", &fixture(), "--yes", "--backup-dir", backups.to_str().unwrap()]);
    assert!(import.status.success(), "{}", stderr(&import));
    assert!(stderr(&import).contains("verified"), "{}", stderr(&import));
    let saved: Vec<_> = std::fs::read_dir(&backups).unwrap().map(|e| e.unwrap().path()).collect();
    assert_eq!(saved.len(), 1);
    assert_eq!(board_view(&saved[0]), board_view(Path::new(&fixture())));
}

#[test]
fn an_export_cut_short_writes_no_file_and_says_why() {
    let sim = sim(&["--tcp", "127.0.0.1:0", "--state", &fixture(), "--faults", "disconnect-after=4"]);
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("never.json");
    let export = run(&["export", "--port", &sim.port, "--out", out.to_str().unwrap(), "--timeout-ms", "300"]);
    assert_eq!(export.status.code(), Some(1));
    let message = stderr(&export);
    assert!(message.contains("was not written"), "{message}");
    assert!(message.contains("lost"), "{message}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "no file, not even a temporary one");
}

#[test]
fn an_invalid_project_is_not_imported() {
    let sim = sim(&["--tcp", "127.0.0.1:0"]);
    let dir = tempfile::tempdir().unwrap();
    let broken = dir.path().join("broken.json");
    let text = std::fs::read_to_string(fixture()).unwrap().replace("\"action_id\": 2,", "\"action_id\": 42,");
    std::fs::write(&broken, text).unwrap();
    let import = run(&["import", "--port", &sim.port, "--in", broken.to_str().unwrap(), "--yes", "--no-backup"]);
    assert_eq!(import.status.code(), Some(1));
    assert!(stderr(&import).contains("action 42 does not exist"), "{}", stderr(&import));
    assert!(stderr(&import).contains("nothing was written"), "{}", stderr(&import));
}

#[test]
fn a_missing_port_says_what_to_try() {
    let output = run(&["board", "info", "--port", "/dev/ttyDOES-NOT-EXIST"]);
    assert_eq!(output.status.code(), Some(1));
    assert!(stderr(&output).contains("servo-studio ports"), "{}", stderr(&output));
}

#[cfg(unix)]
#[test]
fn sim_on_a_pty_serves_the_board() {
    let sim = sim(&["--pty", "--state", &fixture()]);
    assert!(sim.port.starts_with("/dev/"), "{}", sim.port);
    let info = run(&["board", "info", "--port", &sim.port]);
    assert!(info.status.success(), "{}", stderr(&info));
    assert!(String::from_utf8_lossy(&info.stdout).contains("project id: 20261121"));
}

#[test]
fn ports_lists_without_failing() {
    let output = run(&["ports"]);
    assert!(output.status.success(), "{}", stderr(&output));
}
