//! Settings → Remote control… in the editor: the same server as `servo-studio
//! serve`, on the show window's boards. Off until its box is ticked; ticked,
//! it connects the show's boards and listens; a real HTTP client then plays
//! a macro on an emulated board; disconnecting the boards turns it off.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Duration;

use egui_kittest::kittest::Queryable;
use servo_studio::project::Project;
use servo_studio::show::{Cue, Show, Start};
use servo_studio::ui::Action;
use servo_studio::ui::show::ShowAction;
use servo_studio::ui::{Language, Tab};

use crate::cli::play::{Stage, device, logged_until, swinging, waving};
use crate::common;

/// An HTTP client that reads every answer, whatever its status.
fn agent() -> ureq::Agent {
    ureq::Agent::config_builder().http_status_as_error(false).build().into()
}

/// `POST /devices/board/play` of macro `macro_id` to remote control at `addr`, as a client
/// sends it: the answer's status and body.
fn play_through_remote(addr: std::net::SocketAddr, macro_id: impl std::fmt::Display) -> (u16, String) {
    let body = format!(r#"{{"what": "{macro_id}"}}"#);
    let played = agent()
        .post(&format!("http://{addr}/devices/board/play"))
        .header("Content-Type", "application/json")
        .send(&body)
        .unwrap();
    (played.status().as_u16(), played.into_body().read_to_string().unwrap())
}

#[test]
fn the_editor_serves_remote_control_on_the_shows_boards_until_they_are_let_go() {
    let show = Show {
        devices: vec![device("skull", swinging(400)), device("plen", waving())],
        sound: None,
        cues: vec![Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(1) }],
    };
    let stage = Stage::new(&show, &[]);
    let mut app = common::ui::editor(Project::servo(common::sample_biped()));
    app.desks.show.remote.listen = "127.0.0.1:0".into();
    let mut harness = common::ui::showing(app, Tab::Servos, (1280.0, 1400.0));
    // Settings → Remote control… opens its window, off.
    harness.get_by_label("Settings").click();
    harness.run();
    harness.get_by_label("Remote control…").click();
    harness.run();
    harness.get_by_label("Serve remote control (HTTP + OSC)");
    assert!(!harness.state().desks.show.remote.serving(), "off until asked");
    // The show open (its window over this one), its box ticked: what the box sends.
    let app = harness.state_mut();
    app.apply(Action::Show(ShowAction::Open(stage.dir.path().join("show.json"))));
    let session = app.desks.show.session.as_mut().unwrap();
    session.ports = stage.device_args().chunks(2).map(|pair| pair[1].split_once('=').unwrap().1.to_string()).collect();
    app.apply(Action::Show(ShowAction::Remote(true)));
    common::ui::run_until(&mut harness, "served on answered boards", |app| {
        app.desks.show.remote.serving()
            && app.desks.show.linked.as_ref().is_some_and(servo_studio::ui::show::Linked::all_answered)
    });
    let said = harness.state().desks.show.remote.said.clone().unwrap().in_(Language::English).to_string();
    assert!(said.starts_with("listening on http://127.0.0.1:"), "{said}");
    let url = format!("http://{}", harness.state().desks.show.remote.addr().unwrap());
    let agent: ureq::Agent = ureq::Agent::config_builder().http_status_as_error(false).build().into();
    let played = agent
        .post(&format!("{url}/devices/skull/play"))
        .header("Content-Type", "application/json")
        .send(r#"{"what": "show"}"#)
        .unwrap();
    assert_eq!(played.status().as_u16(), 200);
    logged_until(stage.log("skull"), "ExecuteMacroRequest", Duration::from_secs(30));
    // The boards let go: the remote control with them.
    harness.get_by_label("Disconnect the boards").click();
    harness.run();
    assert!(!harness.state().desks.show.remote.serving());
    let said = harness.state().desks.show.remote.said.clone().unwrap().in_(Language::English).to_string();
    assert!(said.contains("the boards were disconnected"), "{said}");
    assert!(agent.get(&format!("{url}/devices")).call().is_err(), "nothing listens any more");
}

/// Remote control turned on for a plain project serves the board the editor
/// is connected to: the editor lets its port go, the project's device takes
/// it, a macro played over HTTP reaches that board, and once remote control
/// stops the editor is connected to it again.
#[test]
fn remote_control_on_a_plain_project_serves_the_board_the_editor_is_connected_to() {
    use servo_studio::sim::{ServoSim, SimConfig, SimEvent, spawn_tcp};
    let project = Project::servo(common::sample_biped());
    let image = servo_studio::device::servo::ServoImage::from_project(&project.servo).unwrap();
    let board = spawn_tcp(
        ServoSim::new(SimConfig::default(), image),
        servo_studio::sim::LOOPBACK_ANY,
        servo_studio::link::no_waker(),
    )
    .unwrap();
    let port = board.port_name.clone();
    let macro_id = project.servo.macros[0].id;
    let mut app = common::ui::editor(project);
    app.desks.show.remote.listen = "127.0.0.1:0".into();
    app.apply(Action::Connect { port: port.clone(), baud: 115_200 });
    let mut harness = common::ui::showing(app, Tab::Servos, (1280.0, 800.0));
    common::ui::run_until(&mut harness, "the editor connected", |app| app.link.is_some());

    harness.state_mut().apply(Action::Show(ShowAction::Remote(true)));
    assert!(harness.state().link.is_none(), "the editor let its port go");
    common::ui::run_until(&mut harness, "served on the answered board", |app| {
        app.desks.show.remote.serving()
            && app.desks.show.linked.as_ref().is_some_and(servo_studio::ui::show::Linked::all_answered)
    });
    let said = harness.state().status.clone().unwrap().text;
    assert!(said.contains(&port) && said.contains("served to remote control"), "{said}");
    let addr = harness.state().desks.show.remote.addr().unwrap();
    assert_eq!(play_through_remote(addr, macro_id).0, 200);
    let deadline = std::time::Instant::now() + Duration::from_secs(30);
    loop {
        match board.events().recv_deadline(deadline) {
            Ok(servo_studio::link::LinkEvent::Driver(SimEvent::MacroSteps { macro_id: played, .. }))
                if played == macro_id =>
            {
                break;
            }
            Ok(_) => {}
            Err(_) => panic!("the board never received the macro"),
        }
    }

    // Remote control off: the editor is connected to its board again.
    harness.state_mut().apply(Action::Show(ShowAction::Remote(false)));
    common::ui::run_until(&mut harness, "the editor connected again", |app| app.link.is_some());
    assert!(!harness.state().link.as_ref().unwrap().is_demo());
    assert!(harness.state().desks.show.project_without_port(), "the port is the editor's again");
}

/// The same with the built-in demo board: served as the same emulated board
/// on a loopback port; the editor's demo comes back when remote control stops.
#[test]
fn remote_control_on_a_plain_project_serves_the_editors_demo_board() {
    let project = Project::servo(common::sample_biped());
    let macro_id = project.servo.macros[0].id;
    let mut app = common::ui::editor(project);
    app.desks.show.remote.listen = "127.0.0.1:0".into();
    app.apply(Action::ConnectDemo);
    let mut harness = common::ui::showing(app, Tab::Servos, (1280.0, 800.0));
    harness.state_mut().apply(Action::Show(ShowAction::Remote(true)));
    common::ui::run_until(&mut harness, "served on the answered board", |app| {
        app.desks.show.remote.serving()
            && app.desks.show.linked.as_ref().is_some_and(servo_studio::ui::show::Linked::all_answered)
    });
    let addr = harness.state().desks.show.remote.addr().unwrap();
    let (status, answer) = play_through_remote(addr, macro_id);
    assert_eq!(status, 200);
    // Started: the served board answered the macro's start.
    assert!(answer.contains(r#""as":"started""#) && answer.contains(r#""device":"board""#), "{answer}");
    let status = agent().get(&format!("http://{addr}/devices/board")).call().unwrap();
    assert_eq!(status.status().as_u16(), 200);
    harness.state_mut().apply(Action::Show(ShowAction::Remote(false)));
    common::ui::run_until(&mut harness, "the demo board back", |app| {
        app.link.as_ref().is_some_and(|link| link.is_demo())
    });
}
