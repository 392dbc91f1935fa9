//! Settings → Remote control… in the editor: the same server as `servo-studio
//! serve`, on the show window's boards. Off until its box is ticked; ticked,
//! it connects the show's boards and listens; a real HTTP client then plays
//! a macro on an emulated board; disconnecting the boards turns it off.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Duration;

use egui_kittest::kittest::Queryable;
use servo_studio::project::Project;
use servo_studio::show::{Cue, Show, Start};
use servo_studio::ui::Tab;
use servo_studio::ui::show::ShowAction;

use crate::cli::play::{Stage, device, logged_until, swinging, waving};
use crate::common;

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
    app.apply(servo_studio::ui::Action::Show(ShowAction::Open(stage.dir.path().join("show.json"))));
    let session = app.desks.show.session.as_mut().unwrap();
    session.ports = stage.device_args().chunks(2).map(|pair| pair[1].split_once('=').unwrap().1.to_string()).collect();
    app.apply(servo_studio::ui::Action::Show(ShowAction::Remote(true)));
    common::ui::run_until(&mut harness, "served on answered boards", |app| {
        app.desks.show.remote.serving()
            && app.desks.show.linked.as_ref().is_some_and(servo_studio::ui::show::Linked::all_answered)
    });
    let said = harness.state().desks.show.remote.said.clone().unwrap();
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
    let said = harness.state().desks.show.remote.said.clone().unwrap();
    assert!(said.contains("the boards were disconnected"), "{said}");
    assert!(agent.get(&format!("{url}/devices")).call().is_err(), "nothing listens any more");
}
