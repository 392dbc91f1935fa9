//! Connecting from the editor: opening a port never blocks the window, can be
//! cancelled, and every failure reads as one sentence in the interface's language.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::net::SocketAddr;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;
use egui_kittest::Harness;
use egui_kittest::kittest::{Queryable, by};
use servo_studio::device::servo::ServoImage;
use servo_studio::link::{Connection, LineSettings, Opener, Waker, open};
use servo_studio::project::{Family, ServoProject};
use servo_studio::sim::{Faults, ServoSim, SimConfig, spawn_in_memory};
use servo_studio::ui::{Action, Language, StudioApp, Tab};

/// A waker that tells the test when the app has something new.
fn waker() -> (Waker, Receiver<()>) {
    let (sender, woken) = crossbeam_channel::unbounded();
    (
        Arc::new(move || {
            let _ = sender.send(());
        }),
        woken,
    )
}

fn app(opener: Opener, waker: Waker) -> StudioApp {
    let data = tempfile::tempdir().unwrap().keep();
    StudioApp::new(ServoProject::default(), None, waker).with_data_dir(data).with_opener(opener)
}

fn harness(app: StudioApp) -> Harness<'static, StudioApp> {
    common::ui::window(app, (1300.0, 800.0))
}

/// Pumps the app each time it is woken, until `done` or 10 s.
fn wait_for(app: &mut StudioApp, woken: &Receiver<()>, what: &str, done: impl Fn(&StudioApp) -> bool) {
    let deadline = Instant::now() + Duration::from_secs(10);
    app.pump(Instant::now());
    while !done(app) {
        assert!(woken.recv_deadline(deadline).is_ok(), "timed out waiting for {what}: {:?}", app.status);
        app.pump(Instant::now());
    }
}

/// An opener that blocks until released, then hands out a connection to an
/// emulated servo board (a USB adapter that takes its time).
fn slow_opener() -> (Opener, crossbeam_channel::Sender<()>, Receiver<Connection>) {
    let (release, released) = crossbeam_channel::unbounded::<()>();
    let (peers_tx, peers) = crossbeam_channel::unbounded();
    let opener: Opener = Arc::new(move |_, _| {
        released.recv_timeout(Duration::from_secs(30)).expect("the test releases the opener");
        let (board_end, client_end) = Connection::memory_pair();
        peers_tx.send(board_end).unwrap();
        Ok(client_end)
    });
    (opener, release, peers)
}

#[test]
fn a_slow_port_keeps_frames_coming_shows_connecting_and_can_be_cancelled() {
    let (opener, release, peers) = slow_opener();
    let (waker, _woken) = waker();
    let mut harness = harness(app(opener, waker));
    harness.run_steps(2);
    harness.state_mut().apply(Action::Connect { port: "/dev/ttyUSB-slow".into(), baud: 115_200 });
    // The opener is blocked: the window keeps drawing frames meanwhile.
    for _ in 0..5 {
        harness.step();
    }
    assert!(harness.state().links.connecting.is_some());
    assert!(harness.query_all_by_label_contains("connecting to /dev/ttyUSB-slow…").next().is_some());
    harness.get_by_label("Cancel").click();
    harness.run_steps(2);
    assert!(harness.state().links.connecting.is_none());
    assert_eq!(harness.state().status.as_ref().unwrap().text, "stopped connecting to /dev/ttyUSB-slow");
    // When the port opens after all, the cancelled connection is closed at once.
    release.send(()).unwrap();
    let mut board_end = peers.recv_timeout(Duration::from_secs(10)).unwrap();
    let mut byte = [0u8; 1];
    let read = board_end.reader_mut().read(&mut byte).unwrap();
    assert_eq!(read, 0, "the cancelled connection was closed");
    harness.run_steps(2);
    assert!(harness.state().link.is_none());
}

#[test]
fn a_slow_port_that_opens_connects_and_talks_to_the_board() {
    let (opener, release, peers) = slow_opener();
    let (waker, woken) = waker();
    let mut app = app(opener, waker.clone());
    app.apply(Action::Connect { port: "/dev/ttyUSB-slow".into(), baud: 115_200 });
    assert!(app.link.is_none() && app.links.connecting.is_some());
    release.send(()).unwrap();
    let board_end = peers.recv_timeout(Duration::from_secs(10)).unwrap();
    let image = ServoImage { project_id: 77, ..ServoImage::default() };
    let _board = servo_studio::link::spawn(board_end, ServoSim::new(SimConfig::default(), image), waker).unwrap();
    wait_for(&mut app, &woken, "the project id", |app| {
        common::ui::servo_board(app).is_some_and(|servo| servo.project_id == Some(77))
    });
    assert!(app.links.connecting.is_none());
    assert_eq!(app.status.as_ref().unwrap().text, "connected to /dev/ttyUSB-slow");
}

/// A listener whose accept queue is full: the kernel drops further SYNs, so a
/// connect to it hangs until its timeout, all on 127.0.0.1.
fn unanswering_address() -> (socket2::Socket, Vec<std::net::TcpStream>, SocketAddr) {
    let socket = socket2::Socket::new(socket2::Domain::IPV4, socket2::Type::STREAM, None).unwrap();
    socket.bind(&SocketAddr::from(([127, 0, 0, 1], 0)).into()).unwrap();
    socket.listen(0).unwrap();
    let address = socket.local_addr().unwrap().as_socket().unwrap();
    let mut queued = Vec::new();
    for _ in 0..8 {
        match std::net::TcpStream::connect_timeout(&address, Duration::from_millis(200)) {
            Ok(stream) => queued.push(stream),
            Err(_) => break, // the queue is full
        }
    }
    (socket, queued, address)
}

#[test]
fn a_tcp_connect_that_times_out_says_so_and_the_window_keeps_drawing() {
    let (_listener, _queued, address) = unanswering_address();
    // The real opener, with a short connect timeout.
    let opener: Opener = Arc::new(|port, settings| {
        open(port, &LineSettings { connect_timeout: Duration::from_millis(300), ..*settings })
    });
    let (waker, woken) = waker();
    let mut harness = harness(app(opener, waker));
    let port = format!("tcp://{address}");
    harness.state_mut().apply(Action::Connect { port: port.clone(), baud: 115_200 });
    harness.step();
    assert!(harness.query_all_by_label_contains("connecting to tcp://").next().is_some());
    let deadline = Instant::now() + Duration::from_secs(10);
    while harness.state().links.connecting.is_some() {
        assert!(woken.recv_deadline(deadline).is_ok(), "the connect never ended");
        harness.step();
        common::ui::wait_for_news();
    }
    let status = harness.state().status.clone().unwrap();
    assert!(status.is_error);
    assert_eq!(
        status.text,
        format!("{port}: no answer within 300 ms. Is the address right, the bridge switched on and on this network?")
    );
    assert!(harness.state().link.is_none());
}

#[test]
fn a_bad_port_is_one_readable_sentence_in_either_language() {
    let (waker, woken) = waker();
    let mut app = app(servo_studio::link::system_opener(), waker);
    app.apply(Action::Connect { port: "/dev/ttyNOPE-servo".into(), baud: 115_200 });
    wait_for(&mut app, &woken, "the open to fail", |app| app.links.connecting.is_none());
    let status = app.status.clone().unwrap();
    assert!(status.is_error && status.text.contains("servo-studio ports"), "{}", status.text);
    assert!(app.link.is_none());

    app.apply(Action::SetLanguage(Language::TraditionalChinese));
    app.apply(Action::Connect { port: "/dev/ttyNOPE-servo".into(), baud: 115_200 });
    wait_for(&mut app, &woken, "the open to fail", |app| app.links.connecting.is_none());
    let status = app.status.clone().unwrap();
    assert!(status.is_error && status.text.starts_with("/dev/ttyNOPE-servo：找不到此連接埠"), "{}", status.text);
}

#[test]
fn the_family_chooser_hides_the_panels_that_do_not_apply() {
    let (waker, _woken) = waker();
    let mut harness = harness(app(servo_studio::link::system_opener(), waker));
    harness.run_steps(2);
    for tab in ["Servos", "Actions", "Macros", "Joystick", "Board", "Packet log"] {
        assert!(harness.query_all_by_label(tab).next().is_some(), "{tab} is offered for a servo board");
    }
    harness.get_by_label("Hardware").click();
    harness.run_steps(2);
    harness.get_by_label("rFLEX base").click();
    harness.run_steps(3);
    assert_eq!(harness.state().document.project.family, Family::Rflex);
    for tab in ["Servos", "Actions", "Macros", "Joystick", "Board"] {
        assert!(harness.query_all_by_label(tab).next().is_none(), "{tab} is hidden for an rFLEX base");
    }
    for tab in ["Drive", "Telemetry", "Packet log"] {
        assert!(harness.query_all_by_label(tab).next().is_some(), "{tab} is offered for an rFLEX base");
    }
    assert_eq!(harness.state().window.tab, Tab::Drive, "the first panel of the family");
    assert!(harness.query_all_by_label("Robot").next().is_some(), "the robot preset sits beside the family");
    // PLEN2: its own panels, the joystick tables still hidden.
    harness.state_mut().apply(Action::SetFamily(Family::Plen2));
    harness.run_steps(2);
    for tab in ["Joints", "Motions", "Play lists", "Board", "Packet log"] {
        assert!(harness.query_all_by_label(tab).next().is_some(), "{tab} is offered for PLEN2");
    }
    assert!(harness.query_all_by_label("Joystick").next().is_none());
    harness.state_mut().apply(Action::Undo);
    // The switch is one undo step; the servo panels come back.
    harness.state_mut().apply(Action::Undo);
    harness.run_steps(2);
    assert_eq!(harness.state().document.project.family, Family::Servo);
    assert!(harness.query_all_by_label("Servos").next().is_some());
}

#[test]
fn a_lost_link_is_one_whole_sentence_in_traditional_chinese() {
    let (waker, woken) = waker();
    let mut app = app(servo_studio::link::system_opener(), waker.clone());
    app.apply(Action::SetLanguage(Language::TraditionalChinese));
    let faults = Faults { disconnect_after: Some(2), ..Faults::default() };
    let sim = ServoSim::new(SimConfig { faults, ..SimConfig::default() }, ServoImage::default());
    let (sim, connection) = spawn_in_memory(sim, waker.clone()).unwrap();
    let handle = servo_studio::device::servo::ServoHandle::over(connection, None, waker).unwrap();
    app.link = Some(servo_studio::ui::BoardLink::new(Box::new(handle), "a board"));
    wait_for(&mut app, &woken, "the disconnect", |app| app.link.is_none());
    drop(sim);
    assert_eq!(
        app.status.as_ref().unwrap().text,
        "與控制板的連線已中斷（另一端關閉了連接埠）。專案未變更，準備好後請重新連線。"
    );
}

#[test]
fn gui_demo_without_a_file_opens_the_sample_robot_on_the_demo_board() {
    let (waker, woken) = waker();
    let start = servo_studio::ui::Start { demo: true, ..servo_studio::ui::Start::default() };
    let mut app = start.into_app(waker, None);
    assert_eq!(app.document.project, servo_studio::ui::sample_project());
    assert_eq!(app.document.project.servo.servos.len(), 16);
    assert!(!app.document.dirty);
    // The demo board holds the sample: its project id comes back.
    wait_for(&mut app, &woken, "the demo board's project id", |app| {
        common::ui::servo_board(app).is_some_and(|servo| servo.project_id == Some(1601))
    });
}

#[test]
fn the_family_used_last_is_remembered_but_a_projects_family_wins() {
    let remembered = servo_studio::ui::Remembered { family: Family::Plen2, ..Default::default() };
    let fresh = servo_studio::ui::Start::default().into_app(servo_studio::link::no_waker(), Some(remembered.clone()));
    assert_eq!(fresh.document.project.family, Family::Plen2, "a new project takes the family used last");
    assert_eq!(fresh.remembered().family, Family::Plen2);

    let project = servo_studio::project::Project::empty(Family::Servo);
    let start = servo_studio::ui::Start { project: Some(project), ..servo_studio::ui::Start::default() };
    let opened = start.into_app(servo_studio::link::no_waker(), Some(remembered));
    assert_eq!(opened.document.project.family, Family::Servo, "an opened project keeps its own family");

    let start = servo_studio::ui::Start { family: Some(Family::Rflex), ..servo_studio::ui::Start::default() };
    let chosen = start.into_app(servo_studio::link::no_waker(), None);
    assert_eq!(chosen.document.project.family, Family::Rflex, "--protocol picks the family");
}

#[test]
fn the_port_field_shows_what_the_link_is_to_while_connected() {
    let (waker, _woken) = waker();
    let mut harness = harness(app(servo_studio::link::system_opener(), waker));
    harness.run_steps(2);
    let port = || by().role(egui::accesskit::Role::TextInput).label("Port");
    harness.get(port()).focus();
    harness.get(port()).type_text("/dev/ttyS7");
    harness.run_steps(2);
    assert!(harness.get(port()).value().is_some_and(|value| value.ends_with("/dev/ttyS7")));
    harness.get_by_label("Demo board").click();
    harness.run_steps(3);
    assert!(harness.state().link.is_some());
    // Not the port typed before: the demo board has none.
    assert_eq!(harness.get(port()).value().as_deref(), Some("Demo board"));
    harness.get_by_label("Disconnect").click();
    harness.run_steps(2);
    assert!(harness.get(port()).value().is_some_and(|value| value.ends_with("/dev/ttyS7")), "the typed port is kept");
}
