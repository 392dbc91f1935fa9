//! The connection doctor in the window: Find board names what answers on a
//! port and connects to it as that family; Hardware = Auto does both at once;
//! a link lost to a pulled cable is made again when the same device comes back
//! (a pseudo-terminal removed and made again behind the same path), and not
//! when another device appears there.

#![cfg(unix)]
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use common::ui::{run_until, window};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::link::{LinkEvent, PortInfo, no_waker, system_opener};
use servo_studio::project::{Family, Project, ServoProject};
use servo_studio::sim::{Plen2Sim, Plen2SimCommand, Plen2SimEvent, Plen2Timing, SimHandle, spawn_pty};
use servo_studio::ui::{Action, StudioApp};

type Robot = SimHandle<Plen2SimCommand, Plen2SimEvent>;

/// The ports the window's lister sees: what the test puts there.
type Listed = Arc<Mutex<Vec<PortInfo>>>;

fn app(project: impl Into<Project>, listed: &Listed) -> Harness<'static, StudioApp> {
    let listed = listed.clone();
    let lister = Arc::new(move || Ok(listed.lock().unwrap().clone()));
    let data = tempfile::tempdir().unwrap().keep();
    let app = StudioApp::new(project, None, no_waker())
        .with_data_dir(data)
        .with_opener(system_opener())
        .with_port_lister(lister);
    window(app, (1300.0, 800.0))
}

fn robot() -> Robot {
    spawn_pty(Plen2Sim::new(Plen2Timing::default()), no_waker()).unwrap()
}

/// A device node as udev makes one: a stable path (`/dev/serial/by-id/…`)
/// that points at the pseudo-terminal of the moment.
fn plug(path: &Path, robot: &Robot) {
    let _ = std::fs::remove_file(path);
    std::os::unix::fs::symlink(&robot.port_name, path).unwrap();
}

fn listed_as(path: &Path, description: &str) -> Vec<PortInfo> {
    vec![PortInfo { name: path.to_string_lossy().into_owned(), description: description.into() }]
}

/// The cable is pulled: the device node goes from the list and the disk, the
/// robot behind it is gone, and the window's link ends.
fn pull(harness: &mut Harness<'static, StudioApp>, listed: &Listed, path: &Path, robot: Robot) {
    listed.lock().unwrap().clear();
    std::fs::remove_file(path).unwrap();
    drop(robot);
    run_until(harness, "the link to end", |app| app.link.is_none());
}

/// Plugged in: a new robot on a new pseudo-terminal behind `path`, listed as `description`.
fn plug_in(listed: &Listed, path: &Path, description: &str) -> Robot {
    let robot = robot();
    plug(path, &robot);
    *listed.lock().unwrap() = listed_as(path, description);
    robot
}

/// Whether `robot` was asked `<VI` (a link was made to it: the PLEN2's connect probe).
fn was_asked(robot: &Robot) -> bool {
    robot
        .events()
        .try_iter()
        .any(|event| matches!(event, LinkEvent::Driver(Plen2SimEvent::Executed(command)) if command.code() == "<VI"))
}

#[test]
fn find_board_names_the_plen2_and_connects_to_it_as_one() {
    let robot = robot();
    let listed: Listed = Arc::new(Mutex::new(vec![PortInfo {
        name: robot.port_name.clone(),
        description: "USB 2341:8037 PLEN2".into(),
    }]));
    // A servo-board document: the doctor finds a PLEN2 all the same.
    let mut harness = app(ServoProject::default(), &listed);
    run_until(&mut harness, "the port list", |app| !app.links.ports.is_empty());
    harness.get_by_label("Find board").click();
    harness.step();
    assert!(harness.state().finding_board(), "asked off the frame");
    run_until(&mut harness, "the probe", |app| !app.finding_board());
    let found = format!("{}: PLEN2 Cytisus 1.4.2 at 2000000 baud; link: first byte after", robot.port_name);
    assert!(harness.query_all_by_label_contains(&found).next().is_some(), "{:?}", harness.state().status);
    assert!(harness.state().link.is_none(), "Find board only finds");
    harness.get_by_label("Connect to it").click();
    run_until(&mut harness, "the link", |app| app.link.is_some());
    assert_eq!(harness.state().document.project.family, Family::Plen2, "the document became a PLEN2 project");
    assert_eq!(harness.state().link.as_ref().unwrap().family(), Family::Plen2);
    harness.run_steps(2);
    // Play on board with a sound waits the latency the doctor measured on this port.
    assert!(harness.state().desks.sound.link_latency().is_some(), "the doctor's measured latency reaches the sound");
    // One undo step puts the family back (once disconnected).
    harness.state_mut().apply(Action::Disconnect);
    harness.state_mut().apply(Action::Undo);
    assert_eq!(harness.state().document.project.family, Family::Servo);
}

#[test]
fn hardware_auto_connects_as_the_family_that_answered_and_says_when_nothing_did() {
    let base = spawn_pty(servo_studio::sim::RflexSim::new(Default::default()), no_waker()).unwrap();
    let listed: Listed = Arc::new(Mutex::new(Vec::new()));
    let mut harness = app(ServoProject::default(), &listed);
    harness.state_mut().apply(Action::FindBoard { port: base.port_name.clone(), connect: true });
    run_until(&mut harness, "the link", |app| app.link.is_some());
    assert_eq!(harness.state().document.project.family, Family::Rflex);
    assert_eq!(harness.state().link.as_ref().unwrap().family(), Family::Rflex);
    harness.state_mut().apply(Action::Disconnect);

    let silent = common::peer(common::Chatter::Silent);
    harness.state_mut().apply(Action::FindBoard { port: silent.port.clone(), connect: true });
    run_until(&mut harness, "the probe", |app| !app.finding_board());
    let status = harness.state().status.clone().unwrap();
    assert!(status.is_error && status.text.starts_with("cannot connect automatically"), "{status:?}");
    assert!(status.text.contains("nothing answered"), "{status:?}");
    assert!(harness.state().link.is_none());
}

#[test]
fn a_pulled_cable_reconnects_when_the_same_device_comes_back_and_not_to_another() {
    let folder = tempfile::tempdir().unwrap();
    let path: PathBuf = folder.path().join("usb-PLEN2-if00");
    let port = path.to_string_lossy().into_owned();
    let first = robot();
    plug(&path, &first);
    let listed: Listed = Arc::new(Mutex::new(listed_as(&path, "USB 2341:8037 PLEN2 serial 42")));
    let plen2 = Project { family: Family::Plen2, ..Project::default() };
    let mut harness = app(plen2, &listed);
    run_until(&mut harness, "the port list", |app| !app.links.ports.is_empty());
    harness.state_mut().apply(Action::Connect { port: port.clone(), baud: 2_000_000 });
    run_until(&mut harness, "the link", |app| app.link.is_some());

    pull(&mut harness, &listed, &path, first);
    assert!(harness.state().waiting_to_reconnect());
    let status = harness.state().status.clone().unwrap();
    assert!(status.text.contains(&format!("Reconnecting by itself when {port} comes back")), "{status:?}");

    // Plugged in again: a new pseudo-terminal behind the same path, listed as the same device.
    let second = plug_in(&listed, &path, "USB 2341:8037 PLEN2 serial 42");
    // Said when it is made (a busy machine's late replies may widen the pacing and say so next).
    let reconnected = format!("reconnected to {port}: the same device came back");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(10);
    while harness.state().link.is_none() {
        assert!(std::time::Instant::now() < deadline, "the link was never made again");
        harness.step();
        common::ui::wait_for_news();
    }
    assert_eq!(harness.state().status.as_ref().unwrap().text, reconnected);
    run_until(&mut harness, "the connect probe", |_| was_asked(&second));
    assert!(!harness.state().waiting_to_reconnect());

    // Pulled again, and another device appears on the path: not connected to by itself.
    pull(&mut harness, &listed, &path, second);
    let third = plug_in(&listed, &path, "USB 1a86:7523 USB Serial (QinHeng)");
    run_until(&mut harness, "the other device to be noticed", |app| {
        app.status.as_ref().is_some_and(|status| status.text.contains("as a different device"))
    });
    assert!(harness.state().link.is_none());
    assert!(!was_asked(&third), "nothing was sent to the other device");

    // Waiting can be given up; the user then connects to the other device themselves.
    harness.get_by_label("Cancel").click();
    harness.step();
    assert!(!harness.state().waiting_to_reconnect());
    harness.state_mut().apply(Action::Connect { port: port.clone(), baud: 2_000_000 });
    run_until(&mut harness, "the link", |app| app.link.is_some());
    run_until(&mut harness, "the connect probe", |_| was_asked(&third));

    // That one is the device now: pulled and back, it is made again.
    pull(&mut harness, &listed, &path, third);
    let fourth = plug_in(&listed, &path, "USB 1a86:7523 USB Serial (QinHeng)");
    run_until(&mut harness, "the link to be made again", |app| app.link.is_some());
    run_until(&mut harness, "the connect probe", |_| was_asked(&fourth));

    // And a link the user closes is never made again by itself.
    harness.state_mut().apply(Action::Disconnect);
    assert!(!harness.state().waiting_to_reconnect());
}

/// "Find a board on every port" asks each listed port in turn and says, for
/// each, what answered — offering to connect to those that did.
#[test]
fn every_port_is_asked_and_each_answer_is_offered() {
    let plen2 = robot();
    let base = spawn_pty(servo_studio::sim::RflexSim::new(Default::default()), no_waker()).unwrap();
    let silent = common::peer(common::Chatter::Silent);
    let listed: Listed = Arc::new(Mutex::new(vec![
        PortInfo { name: plen2.port_name.clone(), description: "USB PLEN2".into() },
        PortInfo { name: base.port_name.clone(), description: "USB FTDI".into() },
        PortInfo { name: silent.port.clone(), description: "PCI".into() },
    ]));
    let mut harness = app(ServoProject::default(), &listed);
    run_until(&mut harness, "the port list", |app| app.links.ports.len() == 3);
    harness.state_mut().apply(Action::FindEveryBoard);
    assert!(harness.state().finding_board());
    run_until(&mut harness, "every port's answer", |app| !app.finding_board());
    for text in [
        format!("{}: PLEN2 Cytisus 1.4.2 at 2000000 baud", plen2.port_name),
        format!("{}: rFLEX base, battery", base.port_name),
        format!("{}: nothing answered", silent.port),
    ] {
        assert!(harness.query_all_by_label_contains(&text).next().is_some(), "{text}");
    }
    assert_eq!(harness.query_all_by_label("Connect to it").count(), 2, "the two that answered");
    assert!(harness.state().link.is_none());
}
