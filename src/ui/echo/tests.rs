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
