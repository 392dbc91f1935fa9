//! Export and import against the emulated board over real pseudo-terminals and
//! TCP, with faults injected.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::needless_pass_by_value)]

use crate::common;

use std::time::Duration;

use common::{exported, rich_project};
use servo_studio::device::servo::DEFAULT_BAUD;
use servo_studio::device::servo::{
    ImportOptions, Item, OpError, Progress, RequestError, ServoBoard, ServoEvent, ServoImage, SessionConfig, export,
    import,
};
use servo_studio::device::{Cancel, Left, Stage};
use servo_studio::link::{LinkEvent, PortName, no_waker};
use servo_studio::project::{self, ServoProject};
use servo_studio::protocol::servo::Message;
use servo_studio::sim::{Faults, ServoSim, SimConfig, SimHandle, spawn_pty, spawn_tcp};

#[derive(Clone, Copy, Debug)]
enum Transport {
    Pty,
    Tcp,
}

fn start(transport: Transport, config: SimConfig, preload: &ServoProject) -> SimHandle {
    let board = ServoSim::new(config, ServoImage::from_project(preload).unwrap());
    match transport {
        Transport::Pty => spawn_pty(board, no_waker()).unwrap(),
        Transport::Tcp => spawn_tcp(board, "127.0.0.1:0".parse().unwrap(), no_waker()).unwrap(),
    }
}

fn connect(sim: &SimHandle, response_timeout: Duration) -> ServoBoard {
    let config = SessionConfig { response_timeout, ..SessionConfig::default() };
    ServoBoard::connect(&PortName::parse(&sim.port_name).unwrap(), DEFAULT_BAUD, config, no_waker()).unwrap()
}

fn quiet(_: &Progress) {}

fn export_from(transport: Transport, config: SimConfig, preload: &ServoProject) -> ServoProject {
    let sim = start(transport, config, preload);
    let board = connect(&sim, Duration::from_secs(2));
    export(&board.requester(), &mut quiet, &Cancel::never()).unwrap()
}

#[test]
fn export_reproduces_a_rich_project_exactly_over_a_pty() {
    let original = rich_project();
    assert_eq!(project::validate_servo(&original), []);
    assert_eq!(export_from(Transport::Pty, SimConfig::default(), &original), exported(original));
}

#[test]
fn export_reproduces_a_rich_project_exactly_over_tcp() {
    let original = rich_project();
    assert_eq!(export_from(Transport::Tcp, SimConfig::default(), &original), exported(original));
}

fn import_then_export(transport: Transport) {
    let sim = start(transport, SimConfig::default(), &ServoProject { project_id: 5, ..ServoProject::default() });
    let board = connect(&sim, Duration::from_secs(2));
    let requester = board.requester();
    let backups = tempfile::tempdir().unwrap();
    let options = ImportOptions { backup_dir: Some(backups.path().to_path_buf()), verify: true, force: false };
    let mut seen = Vec::new();
    let report =
        import(&requester, &rich_project(), &options, &mut |p: &Progress| seen.push(p.clone()), &Cancel::never())
            .unwrap();
    assert!(report.verified);
    // clear, project id, servo parameters, 3 actions, 2 macros, 2 tables, active table
    assert_eq!(report.written, 11);
    let last_write = seen.iter().rev().find(|p| p.phase == servo_studio::device::servo::Phase::Write).unwrap();
    assert_eq!((last_write.done, last_write.total), (11, 11));

    // The backup holds what the board had before: project 5, nothing else.
    let backup = report.backup.unwrap();
    assert!(backup.file_name().unwrap().to_str().unwrap().starts_with("board-backup-"));
    assert_eq!(project::load(&backup).unwrap().servo, ServoProject { project_id: 5, ..ServoProject::default() });

    assert_eq!(export(&requester, &mut quiet, &Cancel::never()).unwrap(), exported(rich_project()));
}

#[test]
fn import_then_export_round_trips_over_a_pty() {
    import_then_export(Transport::Pty);
}

#[test]
fn import_then_export_round_trips_over_tcp() {
    import_then_export(Transport::Tcp);
}

#[test]
fn garbage_and_interleaved_button_events_do_not_disturb_an_export() {
    let faults = Faults { garbage_every: Some(2), button_every: Some(3), ..Faults::default() };
    let sim = start(Transport::Pty, SimConfig { faults, ..SimConfig::default() }, &rich_project());
    let board = connect(&sim, Duration::from_secs(2));
    let requester = board.requester();
    // Subscribe, so that the board sends button events in the middle of the export.
    assert_eq!(
        requester.request(Message::SubscribeButtonEventRequest { subscribe: true }).unwrap(),
        Message::SubscribeButtonEventResponse { ok: true }
    );
    assert_eq!(export(&requester, &mut quiet, &Cancel::never()).unwrap(), exported(rich_project()));
    let buttons: Vec<u32> = board
        .events()
        .try_iter()
        .filter_map(|event| match event {
            LinkEvent::Driver(ServoEvent::Button { button_id, .. }) => Some(button_id),
            _ => None,
        })
        .collect();
    // 14 responses after the subscription's own: a button event before every third.
    assert!(buttons.len() >= 4, "button events seen: {buttons:x?}");
    assert!(buttons.iter().all(|id| id & 0x8000_0000 != 0));
}

#[test]
fn dropped_and_corrupted_responses_are_retried() {
    let faults = Faults { drop_every: Some(4), corrupt_every: Some(7), ..Faults::default() };
    let sim = start(Transport::Tcp, SimConfig { faults, ..SimConfig::default() }, &rich_project());
    // Each dropped response costs a timeout; 500 ms keeps that short and is
    // far beyond what a loaded machine takes to answer (the retries cover the rest).
    let board = connect(&sim, Duration::from_millis(500));
    assert_eq!(export(&board.requester(), &mut quiet, &Cancel::never()).unwrap(), exported(rich_project()));
}

#[test]
fn a_refused_add_stops_the_import_naming_the_item() {
    let faults = Faults { refuse_add: vec![42], ..Faults::default() };
    let sim = start(Transport::Pty, SimConfig { faults, ..SimConfig::default() }, &ServoProject::default());
    let board = connect(&sim, Duration::from_secs(2));
    let options = ImportOptions { backup_dir: None, verify: true, force: false };
    let error = import(&board.requester(), &rich_project(), &options, &mut quiet, &Cancel::never()).unwrap_err();
    assert!(
        matches!(&error.error, OpError::Refused { item } if *item == Item::Action { id: 42, caption: "揮手".into() }),
        "{error:?}"
    );
    assert!(error.to_string().contains("action 42 \"揮手\": the board refused it"), "{error}");
    // Clear, project id, servo parameters and action 1 went before action 42.
    assert!(matches!(&error.left, Left::Partly { reached, total: 11 } if reached.len() == 4), "{:?}", error.left);
}

#[test]
fn a_project_too_large_for_the_board_is_refused_before_anything_is_cleared() {
    let sim = start(
        Transport::Tcp,
        SimConfig { total_memory_bytes: 1000, ..SimConfig::default() },
        &ServoProject { project_id: 9, ..ServoProject::default() },
    );
    let board = connect(&sim, Duration::from_secs(2));
    let options = ImportOptions { backup_dir: None, verify: true, force: false };
    let error = import(&board.requester(), &rich_project(), &options, &mut quiet, &Cancel::never()).unwrap_err();
    assert!(matches!(error.error, OpError::DoesNotFit { total_bytes: 1000, .. }), "{error:?}");
    assert_eq!((error.stage, &error.left), (Stage::Checking, &Left::Untouched));
    assert!(error.to_string().contains("nothing was written"), "{error}");
    // Nothing was cleared.
    let still = export(&board.requester(), &mut quiet, &Cancel::never()).unwrap();
    assert_eq!(still.project_id, 9);
}

#[test]
fn an_invalid_project_is_refused_before_anything_is_cleared() {
    let sim = start(Transport::Pty, SimConfig::default(), &rich_project());
    let board = connect(&sim, Duration::from_secs(2));
    let mut broken = rich_project();
    broken.macros[0].commands[0].ratio_percent = 0;
    let options = ImportOptions { backup_dir: None, verify: true, force: false };
    let error = import(&board.requester(), &broken, &options, &mut quiet, &Cancel::never()).unwrap_err();
    assert!(error.to_string().contains("ratio 0 % is outside 1..=100"), "{error}");
    assert_eq!(export(&board.requester(), &mut quiet, &Cancel::never()).unwrap(), exported(rich_project()));
}

#[test]
fn a_disconnect_mid_import_is_a_clear_error_and_the_backup_is_whole() {
    // Frames: memory (1), backup reads (6 + 3 actions + 2 macros + 2 tables = 13),
    // clear (15), project id (16), servo parameters (17), then the link drops.
    let faults = Faults { disconnect_after: Some(17), ..Faults::default() };
    let sim = start(Transport::Pty, SimConfig { faults, ..SimConfig::default() }, &rich_project());
    let board = connect(&sim, Duration::from_secs(2));
    let backups = tempfile::tempdir().unwrap();
    let options = ImportOptions { backup_dir: Some(backups.path().to_path_buf()), verify: true, force: false };
    let mut fresh = rich_project();
    fresh.project_id = 1;
    let error = import(&board.requester(), &fresh, &options, &mut quiet, &Cancel::never()).unwrap_err();
    match &error.error {
        OpError::Request { item, source: RequestError::Disconnected { .. } } => {
            assert_eq!(item.to_string(), "action 1 \"六十步的大動作\"");
        }
        other => panic!("expected a disconnect while writing action 1, got {other:?}"),
    }
    assert!(error.to_string().contains("the link to the board was lost"), "{error}");
    assert!(
        matches!(&error.left, Left::Partly { reached, .. } if reached.iter().map(ToString::to_string).collect::<Vec<_>>() == ["clear all data", "project id 1", "60 servo parameter(s)"]),
        "{:?}",
        error.left
    );
    let files: Vec<_> = std::fs::read_dir(backups.path()).unwrap().map(|entry| entry.unwrap().path()).collect();
    assert_eq!(files.len(), 1, "one backup, no temporary file: {files:?}");
    assert_eq!(error.backup.as_ref(), Some(&files[0]), "the failure names the backup");
    assert_eq!(project::load(&files[0]).unwrap().servo, exported(rich_project()));
    // And the link reports its end.
    let ended = board
        .events()
        .recv_timeout(Duration::from_secs(10))
        .into_iter()
        .chain(board.events().try_iter())
        .any(|event| matches!(event, LinkEvent::Disconnected { .. }));
    assert!(ended);
}

#[test]
fn cancelling_stops_an_export_between_steps() {
    let sim = start(Transport::Tcp, SimConfig::default(), &rich_project());
    let board = connect(&sim, Duration::from_secs(2));
    let (cancel_tx, cancel) = Cancel::new();
    let mut steps = 0;
    let error = export(
        &board.requester(),
        &mut |p: &Progress| {
            if p.done == 3 && steps == 0 {
                steps += 1;
                cancel_tx.send(()).unwrap();
            }
        },
        &cancel,
    )
    .unwrap_err();
    assert!(matches!(error, OpError::Cancelled), "{error:?}");
}
