//! The echo family end to end in the editor, and the proof that it plugged in
//! through the shared files `docs/ARCHITECTURE.md` names, and no other.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

use super::board::BoardEvent;
use super::*;
use crate::link::LinkEvent;
use crate::ui::StudioApp;

fn editor() -> Harness<'static, StudioApp> {
    crate::ui::test_editor(Project::empty(Family::Echo), egui::vec2(1100.0, 700.0))
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
    assert_eq!(
        harness.state().document.project.sections.get(Family::Echo),
        Some(&serde_json::json!({ "home_deg": 0 }))
    );
}

/// Runs a command line in this process, on a thread of its own (its words as typed after `servo-studio`).
fn command_line(words: &[&str]) -> std::thread::JoinHandle<std::process::ExitCode> {
    use clap::Parser;
    let typed = std::iter::once("servo-studio").chain(words.iter().copied());
    let command = crate::cli::Cli::try_parse_from(typed).unwrap().command.expect("a command");
    std::thread::spawn(move || crate::cli::run(command))
}

/// A loopback address nothing listens on (taken from the system, then let go).
fn free_address() -> std::net::SocketAddr {
    std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap()
}

/// Waits until something listens at `at` (polling, up to 30 s).
fn listening(at: std::net::SocketAddr) {
    let deadline = Instant::now() + Duration::from_secs(30);
    while std::net::TcpStream::connect(at).is_err() {
        assert!(Instant::now() < deadline, "nothing listens at {at}");
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// What an emulator's log (`--log`) says, a line each (without the time).
fn log_lines(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    text.lines().filter_map(|line| Some(line.split_once(' ')?.1.to_string())).collect()
}

/// How many lines of an emulator's log `wanted` picks.
fn logged(path: &Path, wanted: impl Fn(&str) -> bool) -> usize {
    log_lines(path).iter().filter(|said| wanted(said)).count()
}

/// Waits (polling, up to 30 s) until more than `seen` lines of an emulator's log are ones `wanted` picks.
fn logged_more(path: &Path, seen: usize, wanted: impl Fn(&str) -> bool) {
    let deadline = Instant::now() + Duration::from_secs(30);
    while logged(path, &wanted) <= seen {
        assert!(
            Instant::now() < deadline,
            "{} never logged it more than {seen} times: {:?}",
            path.display(),
            log_lines(path)
        );
        std::thread::sleep(Duration::from_millis(10));
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

/// The echo family on the command line, as a user runs it, through the seam
/// alone (its emulator and board commands registered in `command.rs`, its show
/// stage, kind of cue and axis in `stage.rs`): `sim --protocol echo` serves
/// its board beside a servo board's; a show file holding its cue is written
/// and read; `play` plays it beside the servo board's macro; `serve` holds
/// both, and over a raw socket a remote poses the echo, is refused a drive by
/// name and STOPs both; SIGTERM ends `serve` as it ends it for a user.
#[test]
fn the_echo_board_plays_in_a_show_beside_a_servo_board_and_is_posed_and_stopped_through_serve() {
    use crate::show::family::FamilyCue;
    use crate::show::{Cue, Show, Start};

    let dir = tempfile::tempdir().unwrap();
    let log = |name: &str| dir.path().join(format!("{name}.log"));
    let fixture = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/project-v2.json");
    let servo_project = crate::project::load(Path::new(fixture)).unwrap();
    let macro_id = servo_project.servo.macros.iter().map(|m| m.id).min().expect("the fixture holds a macro");

    // Its board, and a servo board holding the project, served by `sim`.
    let (skull_at, echo_at) = (free_address(), free_address());
    let (skull_log, echo_log) = (log("skull"), log("echo"));
    let (skull_tcp, echo_tcp) = (skull_at.to_string(), echo_at.to_string());
    let (skull_log_path, echo_log_path) = (skull_log.to_str().unwrap(), echo_log.to_str().unwrap());
    // Serving on TCP runs until the process ends.
    drop(command_line(&[
        "sim",
        "--protocol",
        "servo",
        "--tcp",
        &skull_tcp,
        "--state",
        fixture,
        "--log",
        skull_log_path,
    ]));
    drop(command_line(&["sim", "--protocol", "echo", "--tcp", &echo_tcp, "--log", echo_log_path]));
    listening(skull_at);
    listening(echo_at);
    let refused = command_line(&["sim", "--protocol", "echo", "--tcp", "127.0.0.1:0", "--stuffed"]).join().unwrap();
    assert_eq!(refused, std::process::ExitCode::FAILURE, "an option its emulator does not take is refused");

    let mut show = Show::of_one("skull", servo_project);
    show.add_device("echo", Project::empty(Family::Echo));
    let moved = Start::Family(FamilyCue::named("move", 30.0).unwrap());
    show.cues.push(Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(macro_id) });
    show.cues.push(Cue { device: "echo".into(), at_ms: 100, start: moved });
    assert_eq!(show.problems().len(), 0, "{:?}", show.problems());
    // Its cue in the show file: under its own kind's key, read back as written.
    let text = show.to_json();
    assert!(text.contains("\"move\": 30.0"), "{text}");
    assert_eq!(Show::from_text(&text, "show.json").unwrap().cues, show.cues);
    let show_file = dir.path().join("show.json");
    std::fs::write(&show_file, &text).unwrap();
    let show_path = show_file.to_str().unwrap();
    let (skull_port, echo_port) = (format!("skull=tcp://{skull_at}"), format!("echo=tcp://{echo_at}"));

    // `play`: both devices start on their cues, and the show ends.
    let played = command_line(&["play", show_path, "--device", &skull_port, "--device", &echo_port]);
    assert_eq!(played.join().unwrap(), std::process::ExitCode::SUCCESS);
    logged_more(&skull_log, 0, |said| said.contains("ExecuteMacroRequest"));
    logged_more(&echo_log, 0, |said| said == "M 30");

    // `serve`: posed and stopped by a remote over a raw socket.
    let http_at = free_address();
    let listen = http_at.to_string();
    let served =
        command_line(&["serve", show_path, "--device", &skull_port, "--device", &echo_port, "--listen", &listen]);
    listening(http_at);
    let (code, said) = http(http_at, "GET", "/devices/echo", "");
    assert_eq!((code, said["axes"].clone()), (200, serde_json::json!(["servo"])), "{said}");
    let (code, said) = http(http_at, "POST", "/devices/echo/pose", r#"{"axis": "servo", "value": 45}"#);
    assert_eq!((code, said["value"].as_f64()), (200, Some(45.0)), "{said}");
    logged_more(&echo_log, 0, |said| said == "M 45");
    let (code, said) = http(http_at, "POST", "/devices/echo/drive", r#"{"speed_m_s": 0.1}"#);
    assert_eq!(code, 422, "{said}");
    assert_eq!(said["error"], "echo: an Echo board cannot drive; pose it (POST /devices/echo/pose)");
    // Every servo switched off, holding (as the servo board's emulator logs it).
    let holding = |said: &str| said.contains("is_start: false");
    let stopped = |said: &str| said == "S";
    // What `play` sent reached the boards before `serve` was let in: these counts are all before STOP.
    let (echo_stops, skull_stops) = (logged(&echo_log, stopped), logged(&skull_log, holding));
    let (code, said) = http(http_at, "POST", "/stop", "");
    assert_eq!(code, 200, "{said}");
    logged_more(&echo_log, echo_stops, stopped);
    logged_more(&skull_log, skull_stops, holding);

    // A user's Ctrl-C or kill ends it, every device stopped: exit 143 for SIGTERM.
    signal_hook::low_level::raise(signal_hook::consts::SIGTERM).unwrap();
    assert_eq!(served.join().unwrap(), std::process::ExitCode::from(143));
}
