//! The echo family end to end in the editor, and the proof that it plugged in
//! through the shared files `docs/ARCHITECTURE.md` names, and no other.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

use super::board::BoardEvent;
use super::*;
use crate::link::{LinkEvent, no_waker};
use crate::ui::StudioApp;

fn editor() -> Harness<'static, StudioApp> {
    let data = tempfile::tempdir().unwrap().keep();
    let app = StudioApp::new(Project::empty(Family::Echo), None, no_waker()).with_data_dir(data);
    Harness::builder()
        .with_size(egui::vec2(1100.0, 700.0))
        .with_context_setup(|ctx| {
            crate::ui::fonts::install(ctx);
            crate::ui::Costing::IN_FRAME.install(ctx);
        })
        .build_ui_state(|ui, app: &mut StudioApp| app.show(ui), app)
}

fn run_until(harness: &mut Harness<'static, StudioApp>, what: &str, done: impl Fn(&StudioApp) -> bool) {
    let deadline = Instant::now() + Duration::from_secs(10);
    while !done(harness.state()) {
        assert!(Instant::now() < deadline, "timed out waiting for {what}");
        harness.step();
    }
}

fn echo(app: &StudioApp) -> &EchoUi {
    app.families.of().expect("the echo family is in the editor")
}

#[test]
fn the_echo_board_is_a_family_of_the_editor_moved_live_on_its_own_emulator() {
    let mut harness = editor();
    harness.run_steps(2);
    assert_eq!(harness.state().window.tab, Tab::Echo, "its panel is where the editor opens");
    assert!(harness.query_by_label("Echo").is_some(), "its tab is in the tabs row");
    harness.get_by_label("Demo board").click();
    run_until(&mut harness, "the demo echo board", |app| app.link.is_some());
    assert_eq!(harness.state().status.as_ref().unwrap().text, "connected to the demo echo board");

    harness.get_by_label("+10°").click();
    run_until(&mut harness, "the echo", |app| echo(app).echoed == Some(10));
    let board = harness.state().link.as_ref().and_then(BoardLink::emulated::<EmulatedEcho>).expect("its emulator");
    let events = board.events().clone();
    let moved = events.recv_timeout(Duration::from_secs(10)).expect("the board saw the move");
    assert!(matches!(moved, LinkEvent::Driver(BoardEvent::Moved(10))), "{moved:?}");

    // STOP, the family's way, reaches its board.
    harness.get_by_label("■ STOP").click();
    harness.step();
    let stopped = events.recv_timeout(Duration::from_secs(10)).expect("the board saw STOP");
    assert!(matches!(stopped, LinkEvent::Driver(BoardEvent::Stopped)), "{stopped:?}");
    assert_eq!(harness.state().status.as_ref().unwrap().text, "the echo board stopped");

    // Until Resume, a move is refused (and said).
    let before = echo(harness.state()).pose;
    harness.state_mut().apply(Action::family(EchoAction::Move(40)));
    assert_eq!(echo(harness.state()).pose, before, "refused after STOP");
    assert!(harness.state().status.as_ref().unwrap().text.contains("press Resume"));
    harness.state_mut().apply(Action::Resume);
    // A move is one of its own actions, routed to it alone.
    harness.state_mut().apply(Action::family(EchoAction::Move(500)));
    assert_eq!(echo(harness.state()).pose, 90, "clamped to its range");
    run_until(&mut harness, "the clamped echo", |app| echo(app).echoed == Some(90));
}

/// Files of `src/` outside the echo family's own folder that name it.
fn shared_files_naming_the_echo() -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let own = root.join("src/ui/echo");
    let mut found = Vec::new();
    let mut folders = vec![root.join("src")];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).unwrap() {
            let path: PathBuf = entry.unwrap().path();
            if path.is_dir() {
                if path != own {
                    folders.push(path);
                }
            } else if path.extension().is_some_and(|ending| ending == "rs") {
                let text = std::fs::read_to_string(&path).unwrap();
                if ["Family::Echo", "ui::echo", "mod echo;", "EchoUi"].iter().any(|name| text.contains(name)) {
                    found.push(path.strip_prefix(root).unwrap().display().to_string());
                }
            }
        }
    }
    found.sort();
    found
}

/// The shared files `docs/ARCHITECTURE.md` says a new family touches.
fn named_in_architecture() -> Vec<String> {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/ARCHITECTURE.md")).unwrap();
    let section = text.split("### A fourth family in four files").nth(1).expect("the section").split("\n#").next();
    let mut named: Vec<String> = section
        .unwrap_or_default()
        .lines()
        .filter_map(|line| line.strip_prefix("- `")?.split('`').next().map(str::to_string))
        .collect();
    named.sort();
    named
}

#[test]
fn the_echo_family_touches_only_the_shared_files_named() {
    let touched = shared_files_naming_the_echo();
    assert!(touched.len() <= 4, "at most four shared files: {touched:?}");
    assert_eq!(touched, named_in_architecture(), "the shared edits are the ones ARCHITECTURE.md names");
}

/// The echo keeps a section of its own in the project: set in its panel as
/// one undo step, written under its tag, read back without an unknown key,
/// and checked by the family.
#[test]
fn the_echo_keeps_its_own_project_section_written_read_and_checked() {
    let mut harness = editor();
    harness.run_steps(2);
    harness.get_by_label("+10°").click();
    harness.run_steps(2);
    harness.get_by_label("Set home").click();
    harness.run_steps(2);
    let project = harness.state().document.project.clone();
    assert_eq!(EchoSection::of(&project), EchoSection { home_deg: 10 });
    assert!(harness.query_by_label("home 10°").is_some(), "the panel shows the kept home");

    let text = crate::project::to_json(&project);
    let file: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(file["family"], "echo");
    assert_eq!(file["echo"], serde_json::json!({ "home_deg": 10 }));
    let loaded = crate::project::parse(&text).unwrap();
    assert_eq!(loaded.project, project, "read back as written");
    assert!(loaded.unknown_keys.is_empty(), "{:?}", loaded.unknown_keys);
    assert!(crate::project::validate(&project).is_empty());

    let wrong = text.replace("\"home_deg\": 10", "\"home_deg\": 120");
    let problems = crate::project::validate(&crate::project::parse(&wrong).unwrap().project);
    let said: Vec<String> = problems.iter().map(ToString::to_string).collect();
    assert_eq!(said, ["error: project: the echo servo's home 120° is outside −90..=90°"]);

    // One undo step takes the section away again.
    harness.state_mut().apply(Action::Undo);
    assert_eq!(harness.state().document.project.sections.get(Family::Echo), None);
}

/// What `events` says next that `wanted` picks, within 10 s.
fn next_board_event<E: std::fmt::Debug>(
    events: &crossbeam_channel::Receiver<LinkEvent<E>>,
    what: &str,
    wanted: impl Fn(&E) -> bool,
) -> E {
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        match events.recv_timeout(left) {
            Ok(LinkEvent::Driver(event)) if wanted(&event) => return event,
            Ok(_) => {}
            Err(_) => panic!("the board never saw {what}"),
        }
    }
}

/// An HTTP request over a raw socket to the remote control server; its status and body.
fn http(at: std::net::SocketAddr, method: &str, path: &str, body: &str) -> (u16, serde_json::Value) {
    use std::io::{Read, Write};
    let mut stream = std::net::TcpStream::connect(at).unwrap();
    stream.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    let request = format!(
        "{method} {path} HTTP/1.1\r\nHost: test\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
        body.len()
    );
    stream.write_all(request.as_bytes()).unwrap();
    let mut answer = String::new();
    stream.read_to_string(&mut answer).unwrap();
    let code = answer.split(' ').nth(1).and_then(|code| code.parse().ok()).unwrap_or(0);
    let json = answer.split("\r\n\r\n").nth(1).and_then(|body| serde_json::from_str(body).ok());
    (code, json.unwrap_or_default())
}

/// The echo family takes part in shows and remote control through the seam
/// alone (its show stage, its kind of cue and its axis registered in its own
/// folder, `stage.rs`): a show file holding its cue reads and writes, the show
/// plays it beside a servo board's macro, and the server `servo-studio serve`
/// starts poses it and stops it, asked over a raw socket.
#[test]
fn the_echo_board_plays_in_a_show_beside_a_servo_board_and_is_posed_and_stopped_through_serve() {
    use std::sync::Arc;

    use crate::show::boards::{Boards, Heard};
    use crate::show::family::FamilyCue;
    use crate::show::{Cue, Show, Start};

    let fixture = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/project-v2.json");
    let servo_project = crate::project::load(Path::new(fixture)).unwrap();
    let macro_id = servo_project.servo.macros.iter().map(|m| m.id).min().expect("the fixture holds a macro");
    let image = crate::device::servo::ServoImage::from_project(&servo_project.servo).unwrap();
    let sim_config = crate::sim::SimConfig::default();
    let skull =
        crate::sim::spawn_tcp(crate::sim::ServoSim::new(sim_config, image), crate::sim::LOOPBACK_ANY, no_waker())
            .unwrap();
    let echo_board = crate::sim::spawn_tcp(board::EchoBoard::default(), crate::sim::LOOPBACK_ANY, no_waker()).unwrap();

    let mut show = Show::of_one("skull", servo_project);
    show.add_device("echo", Project::empty(Family::Echo));
    show.devices[0].port = Some(skull.port_name.clone());
    show.devices[1].port = Some(echo_board.port_name.clone());
    let moved = Start::Family(FamilyCue::named("move", 30.0).unwrap());
    show.cues.push(Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(macro_id) });
    show.cues.push(Cue { device: "echo".into(), at_ms: 100, start: moved });
    assert_eq!(show.problems().len(), 0, "{:?}", show.problems());
    // Its cue in the show file: under its own kind's key, read back as written.
    let text = show.to_json();
    assert!(text.contains("\"move\": 30.0"), "{text}");
    assert_eq!(Show::from_text(&text, "show.json").unwrap().cues, show.cues);

    let boards = Arc::new(Boards::connect(&show, no_waker()).unwrap());
    for _ in 0..2 {
        match boards.hear_within(Duration::from_secs(10)) {
            Some(Heard::Linked(_, Ok(_))) => {}
            other => panic!("each device answers: {other:?}"),
        }
    }
    boards.play(&show, None);
    let played = loop {
        match boards.hear_within(Duration::from_secs(10)) {
            Some(Heard::Played(played)) => break played,
            Some(_) => {}
            None => panic!("the show never ended"),
        }
    };
    let ran = played.expect("the show played");
    assert_eq!(ran.sent.len(), 2, "both devices started: {:?}", ran.sent);
    next_board_event(
        skull.events(),
        "its macro",
        |event| matches!(event, crate::sim::SimEvent::MacroSteps { macro_id: id, .. } if *id == macro_id),
    );
    next_board_event(echo_board.events(), "its cue", |event| *event == BoardEvent::Moved(30));

    // Posed and stopped through the remote control server, as `serve` starts it.
    let guard = Arc::new(crate::remote::guard::Guard::new("127.0.0.1:0".parse().unwrap(), None).unwrap());
    let remote = Arc::new(crate::remote::Remote::new(show.clone(), Arc::downgrade(&boards), false));
    let servers = crate::remote::Servers::start("127.0.0.1:0".parse().unwrap(), None, &guard, remote).unwrap();
    let at = servers.http.addr();
    let (code, said) = http(at, "GET", "/devices/echo", "");
    assert_eq!((code, said["axes"].clone()), (200, serde_json::json!(["servo"])), "{said}");
    let (code, said) = http(at, "POST", "/devices/echo/pose", r#"{"axis": "servo", "value": 45}"#);
    assert_eq!((code, said["value"].as_f64()), (200, Some(45.0)), "{said}");
    next_board_event(echo_board.events(), "the remote's pose", |event| *event == BoardEvent::Moved(45));
    let (code, said) = http(at, "POST", "/devices/echo/drive", r#"{"speed_m_s": 0.1}"#);
    assert_eq!(code, 422, "{said}");
    assert_eq!(said["error"], "echo: an Echo board cannot drive");
    let (code, said) = http(at, "POST", "/stop", "");
    assert_eq!(code, 200, "{said}");
    next_board_event(echo_board.events(), "STOP", |event| *event == BoardEvent::Stopped);
    next_board_event(
        skull.events(),
        "STOP",
        // Every servo switched off, holding (read as the emulator logs it, as the suite's STOP tests do).
        |event| matches!(event, crate::sim::SimEvent::Handled(message) if format!("{message:?}").contains("is_start: false")),
    );
}
