//! Nothing blocks a frame: a port scan stuck in a driver and a save to a disk
//! that does not answer leave the window drawing and STOP working. The port
//! lister and the file writer given here block until the test releases
//! them, and fail the test if the window's own thread ever calls them.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::sync::Arc;
use std::time::Duration;

use crossbeam_channel::{Receiver, Sender};
use egui_kittest::kittest::Queryable;
use servo_studio::link::{PortInfo, Waker};
use servo_studio::project::{self, Project};
use servo_studio::ui::{Action, PortLister, ServoAction, StudioApp, files};

/// Longest the test waits for anything (a healthy run takes milliseconds).
const WAIT: Duration = Duration::from_secs(10);

/// A gate the blocked work waits behind: it opens when the test drops its key.
fn gate() -> (Sender<()>, Receiver<()>) {
    crossbeam_channel::bounded(0)
}

/// A writer that says which file it was asked for, then blocks like a network
/// drive that does not answer until the key is dropped — and fails the test
/// if the window's own thread calls it.
fn blocking_writer(
    window_thread: std::thread::ThreadId,
) -> (Sender<()>, Receiver<std::path::PathBuf>, files::FileWriter) {
    let (write_key, write_gate) = gate();
    let (writing_tx, writing) = crossbeam_channel::unbounded();
    let writer: files::FileWriter = Arc::new(move |path: &std::path::Path, bytes: &[u8]| {
        assert_ne!(std::thread::current().id(), window_thread, "a file was written on the window's thread");
        let _ = writing_tx.send(path.to_path_buf());
        let _ = write_gate.recv();
        files::system_writer()(path, bytes)
    });
    (write_key, writing, writer)
}

#[test]
fn a_stuck_port_scan_and_a_slow_save_leave_the_window_drawing_and_stop_working() {
    let window_thread = std::thread::current().id();
    let (scan_key, scan_gate) = gate();
    let (scanning_tx, scanning) = crossbeam_channel::unbounded();
    let lister: PortLister = Arc::new(move || {
        assert_ne!(std::thread::current().id(), window_thread, "the port list was read on the window's thread");
        let _ = scanning_tx.send(());
        // Blocks like a stuck driver until the key is dropped.
        let _ = scan_gate.recv();
        Ok(vec![PortInfo { name: "/dev/ttyTEST0".into(), description: "a port that came back".into() }])
    });
    let (write_key, writing, writer) = blocking_writer(window_thread);
    let (woke, woken) = crossbeam_channel::unbounded();
    let waker: Waker = Arc::new(move || {
        let _ = woke.send(());
    });
    let data = tempfile::tempdir().unwrap();
    let app = StudioApp::new(servo_studio::ui::sample_project(), None, waker)
        .with_data_dir(data.path().to_path_buf())
        .with_port_lister(lister)
        .with_file_writer(writer);
    let mut harness = common::ui::window(app, (1200.0, 800.0));
    harness.state_mut().apply(Action::ConnectDemo);
    harness.step();
    scanning.recv_timeout(WAIT).expect("the port list is being read");

    let saved = data.path().join("robot.json");
    let project_when_saved = harness.state().document.project.clone();
    harness.state_mut().apply(Action::SaveAs(saved.clone()));
    assert_eq!(writing.recv_timeout(WAIT).unwrap(), saved, "the save reached the writer, which now blocks");

    // Both are stuck. The window draws on, says what it is doing, and STOP stops the board.
    for _ in 0..5 {
        harness.step();
    }
    assert!(harness.state().saving());
    let saving = format!("saving… {}", saved.display());
    assert!(harness.query_by_label(&saving).is_some(), "the status line says the save is under way");
    harness.get_by_label("■ STOP").click();
    harness.step();
    let app = harness.state();
    assert!(app.link.as_ref().is_some_and(servo_studio::ui::BoardLink::stopped), "STOP reached the board");
    assert_eq!(app.status.as_ref().unwrap().text, "STOP: every servo stopped where it is, holding torque");
    // An edit made while the file is written stays unsaved.
    harness.state_mut().apply(Action::family(ServoAction::CapturePose { from_board: false }));
    assert!(harness.state().document.dirty);

    drop(write_key);
    harness.state_mut().finish_file_work(Some(WAIT));
    assert!(!harness.state().saving());
    assert_eq!(project::load(&saved).unwrap(), project_when_saved, "the file holds the project as it was saved");
    assert_eq!(harness.state().document.path.as_deref(), Some(saved.as_path()));
    assert!(harness.state().document.dirty, "the edit made during the save is not saved");

    drop(scan_key);
    while harness.state().links.ports.is_empty() {
        woken.recv_timeout(WAIT).expect("the port list arrives");
        harness.step();
        common::ui::wait_for_news();
    }
    assert_eq!(harness.state().links.ports[0].name, "/dev/ttyTEST0");
}

/// Opening and autosaving go through the same worker: a stuck disk does not
/// stop the window, and what was asked arrives in order once it answers.
#[test]
fn an_open_waiting_behind_a_stuck_autosave_arrives_after_it() {
    let window_thread = std::thread::current().id();
    let (write_key, writing, writer) = blocking_writer(window_thread);
    let data = tempfile::tempdir().unwrap();
    let other = data.path().join("other.json");
    let mut other_project = Project::default();
    other_project.servo.project_id = 77;
    project::save(&other, &other_project).unwrap();

    let mut app = StudioApp::new(servo_studio::ui::sample_project(), None, servo_studio::link::no_waker())
        .with_data_dir(data.path().to_path_buf())
        .with_file_writer(writer);
    app.apply(Action::family(ServoAction::CapturePose { from_board: false }));
    assert!(app.document.dirty);
    app.apply(Action::Autosave);
    assert_eq!(writing.recv_timeout(WAIT).unwrap(), data.path().join("recovery.json"));
    app.apply(Action::Open(other.clone()));
    app.apply(Action::UnsavedDiscard);
    app.finish_file_work(None);
    assert_ne!(app.document.project.servo.project_id, 77, "the open waits behind the stuck autosave");

    drop(write_key);
    app.finish_file_work(Some(WAIT));
    assert_eq!(app.document.project.servo.project_id, 77, "then it arrives");
    assert!(files::read_recovery(data.path()).is_some(), "and the autosave was written");
}
