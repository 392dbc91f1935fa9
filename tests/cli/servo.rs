//! The board commands of `servo-studio`, run as a user runs them, against
//! `servo-studio sim` in another process.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::needless_pass_by_value)]

use std::path::Path;
use std::process::{Command, Output, Stdio};

use crate::common;

use common::sim;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

fn fixture() -> String {
    format!("{}/tests/fixtures/project-v1.json", env!("CARGO_MANIFEST_DIR"))
}

fn run(args: &[&str]) -> Output {
    Command::new(EXE).args(args).stdin(Stdio::null()).output().unwrap()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// The board-carried parts of a project file (client-side limits aside).
fn board_view(path: &Path) -> servo_studio::device::servo::ServoImage {
    servo_studio::device::servo::ServoImage::from_project(&servo_studio::project::load(path).unwrap().servo).unwrap()
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
    assert!(printed.contains("battery: 87.0 %"), "{printed}");

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

#[cfg(unix)]
#[test]
fn a_board_holding_content_servo_studio_would_not_author_is_restored_byte_for_byte() {
    use servo_studio::device::servo::ServoImage;
    use servo_studio::project::{self, Project};
    let dir = tempfile::tempdir().unwrap();
    let image = common::unauthorable_image();
    let state = dir.path().join("state.json");
    project::save(&state, &Project::servo(image.to_project())).unwrap();
    let original = sim(&["--pty", "--state", state.to_str().unwrap()]);

    // Export the board as a user would.
    let exported = dir.path().join("exported.json");
    let export = run(&["export", "--port", &original.port, "--out", exported.to_str().unwrap()]);
    assert!(export.status.success(), "{}", stderr(&export));
    let file = project::load(&exported).unwrap();
    let stored: Vec<Option<i32>> =
        file.servo.macros.iter().flat_map(|m| m.commands.iter().map(|c| c.stored_total_ms)).collect();
    assert_eq!(stored, [Some(1234), Some(777), Some(i32::MAX)], "every stored total is kept");

    // Onto an empty board: refused without --force, listing the problems; nothing written.
    let empty = sim(&["--pty"]);
    let refused = run(&["import", "--port", &empty.port, "--in", exported.to_str().unwrap(), "--yes", "--no-backup"]);
    assert_eq!(refused.status.code(), Some(1));
    let message = stderr(&refused);
    for problem in [
        "action 1 \"重複\", step 2: servo 1 already has a step in this action",
        "action 1 \"重複\", step 3: servo 9 does not exist",
        "macro 10 \"懸空\", command 1: macro 999 does not exist",
        "macro 11 \"溢位\", command 1: runs for",
        "button 0x80000010 \"A\": press macro 55 does not exist",
        "--force",
    ] {
        assert!(message.contains(problem), "{problem:?} missing from: {message}");
    }
    let untouched = dir.path().join("untouched.json");
    let check = run(&["export", "--port", &empty.port, "--out", untouched.to_str().unwrap()]);
    assert!(check.status.success(), "{}", stderr(&check));
    assert_eq!(board_view(&untouched), ServoImage::default(), "nothing was written");

    // With --force: restored, verified, and the same records byte for byte.
    let forced =
        run(&["import", "--port", &empty.port, "--in", exported.to_str().unwrap(), "--yes", "--no-backup", "--force"]);
    assert!(forced.status.success(), "{}", stderr(&forced));
    assert!(stderr(&forced).contains("verified"), "{}", stderr(&forced));
    let restored = dir.path().join("restored.json");
    let again = run(&["export", "--port", &empty.port, "--out", restored.to_str().unwrap()]);
    assert!(again.status.success(), "{}", stderr(&again));
    assert_eq!(common::record_bytes(&board_view(&restored)), common::record_bytes(&image));

    // The automatic backup before an upload restores exactly too.
    let backups = dir.path().join("backups");
    std::fs::create_dir(&backups).unwrap();
    let overwrite = run(&[
        "import",
        "--port",
        &original.port,
        "--in",
        &fixture(),
        "--yes",
        "--backup-dir",
        backups.to_str().unwrap(),
    ]);
    assert!(overwrite.status.success(), "{}", stderr(&overwrite));
    let backup: Vec<_> = std::fs::read_dir(&backups).unwrap().map(|e| e.unwrap().path()).collect();
    assert_eq!(backup.len(), 1);
    let third = sim(&["--pty"]);
    let restore =
        run(&["import", "--port", &third.port, "--in", backup[0].to_str().unwrap(), "--yes", "--no-backup", "--force"]);
    assert!(restore.status.success(), "{}", stderr(&restore));
    let from_backup = dir.path().join("from-backup.json");
    assert!(run(&["export", "--port", &third.port, "--out", from_backup.to_str().unwrap()]).status.success());
    assert_eq!(common::record_bytes(&board_view(&from_backup)), common::record_bytes(&image));
}

#[test]
fn commands_that_do_not_apply_to_a_family_say_what_to_use_instead() {
    let output = run(&["export", "--port", "/dev/null", "--out", "x.json", "--protocol", "rflex"]);
    assert_eq!(output.status.code(), Some(1));
    assert!(stderr(&output).contains("servo-studio rflex status"), "{}", stderr(&output));
    let bad = run(&["sim", "--protocol", "nope"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(stderr(&bad).contains("is not a family: use servo, plen2, rflex"), "{}", stderr(&bad));
}

/// A servo project file (project id 5) of `section`'s servos, actions and macros, in `dir`.
fn eased(dir: &Path, section: &str) -> std::path::PathBuf {
    let path = dir.join("eased.json");
    let text = format!(
        r#"{{"format": "servo-studio-project", "version": 2, "family": "servo", "servo": {{"project_id": 5, {section}}}}}"#
    );
    std::fs::write(&path, text).unwrap();
    path
}

/// A step with a curve goes to the board as straight sub-steps run by a macro
/// of their own: the import is verified against that, and what the board then
/// holds, traced at its 10 ms updates, stays within 1° of the curve meant.
#[test]
fn an_eased_step_is_imported_baked_verified_and_plays_within_a_degree_of_its_curve() {
    let dir = tempfile::tempdir().unwrap();
    let authored = eased(
        dir.path(),
        r#""servos": [{"id": 1, "caption": "臂"}, {"id": 2, "caption": "腕"}],
        "actions": [{"id": 1, "caption": "揮手", "steps": [
            {"servo_id": 1, "degree": 90, "interval_10ms": 100, "easing": "ease_in_out"},
            {"servo_id": 2, "degree": -40, "interval_10ms": 50}]}],
        "macros": [{"id": 1, "caption": "show", "commands": [{"kind": "action", "action_id": 1, "loop_count": 2}]}]"#,
    );
    let sim = sim(&["--tcp", "127.0.0.1:0"]);
    let import = run(&["import", "--port", &sim.port, "--in", authored.to_str().unwrap(), "--yes", "--no-backup"]);
    assert!(import.status.success(), "{}", stderr(&import));
    assert!(stderr(&import).contains("verified"), "{}", stderr(&import));
    assert!(stderr(&import).contains("curves stored as straight steps within"), "{}", stderr(&import));
    assert!(!stderr(&import).contains("widened"), "{}", stderr(&import));
    let exported = dir.path().join("board.json");
    let export = run(&["export", "--port", &sim.port, "--out", exported.to_str().unwrap()]);
    assert!(export.status.success(), "{}", stderr(&export));
    let board = servo_studio::project::load(&exported).unwrap().servo;
    assert!(board.actions.len() > 2, "sub-actions for the curve: {}", board.actions.len());
    assert!(board.actions.iter().flat_map(|a| &a.steps).all(|s| s.easing.is_linear()), "the board holds no curves");
    // What the board holds, traced: the curve once (90 · ease-in-out over 1 s), then the second turn holds.
    let csv = dir.path().join("board.csv");
    let traced = run(&["trajectory", exported.to_str().unwrap(), "--macro", "1", "--out", csv.to_str().unwrap()]);
    assert!(traced.status.success(), "{}", stderr(&traced));
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<f64>> =
        text.lines().skip(1).map(|line| line.split(',').map(|field| field.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), 201, "two turns of a second, a row per 10 ms");
    for row in &rows {
        let t = (row[0] / 1000.0).min(1.0);
        let meant = 90.0 * if t < 0.5 { 2.0 * t * t } else { 1.0 - 2.0 * (1.0 - t) * (1.0 - t) };
        assert!((row[1] - meant).abs() <= 1.0, "at {} ms: {} for {meant}", row[0], row[1]);
        let wrist = -40.0 * (row[0] / 500.0).min(1.0);
        assert!((row[2] - wrist).abs() <= 1.0, "the straight step stays straight: {row:?}");
    }
    // The authored project's own trajectory is what the board plays.
    let own_csv = dir.path().join("own.csv");
    let own = run(&["trajectory", authored.to_str().unwrap(), "--macro", "1", "--out", own_csv.to_str().unwrap()]);
    assert!(own.status.success(), "{}", stderr(&own));
    assert_eq!(std::fs::read_to_string(&own_csv).unwrap(), text);
}

/// A board whose memory cannot hold the curves at 1°: the upload widens the
/// tolerance until they fit, says so, and verifies, rather than failing.
#[test]
fn a_board_too_small_for_the_curves_gets_them_at_a_wider_tolerance_and_is_told() {
    use servo_studio::device::servo::ServoImage;
    let dir = tempfile::tempdir().unwrap();
    let authored = eased(
        dir.path(),
        r#""servos": [{"id": 1, "caption": "arm"}],
        "actions": [{"id": 1, "caption": "swing", "steps": [{"servo_id": 1, "degree": 90, "interval_10ms": 300, "easing": "ease_in_out"}]}],
        "macros": [{"id": 1, "caption": "show", "commands": [{"kind": "action", "action_id": 1}]}]"#,
    );
    let project = servo_studio::project::load(&authored).unwrap().servo;
    let (image, _) = ServoImage::within(&project, None).unwrap();
    let at_one_degree = image.footprint_bytes().unwrap();
    let memory = (at_one_degree - 1).to_string();
    let sim = sim(&["--tcp", "127.0.0.1:0", "--memory", &memory]);
    let import = run(&["import", "--port", &sim.port, "--in", authored.to_str().unwrap(), "--yes", "--no-backup"]);
    assert!(import.status.success(), "{}", stderr(&import));
    let said = stderr(&import);
    assert!(said.contains("verified") && said.contains("widened from 1° to fit the board's memory"), "{said}");
    let exported = dir.path().join("board.json");
    assert!(run(&["export", "--port", &sim.port, "--out", exported.to_str().unwrap()]).status.success());
    let held = ServoImage::from_project(&servo_studio::project::load(&exported).unwrap().servo).unwrap();
    assert!(held.footprint_bytes().unwrap() < at_one_degree);
}
