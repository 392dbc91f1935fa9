//! Files and the safety of work: save / open, the unsaved-changes question,
//! drag-and-drop, autosave and recovery after a crash.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::link::no_waker;
use servo_studio::project::{self, Servo, ServoProject};
use servo_studio::ui::{Action, AfterUnsaved, StudioApp};

/// Longest a test waits for file work (it is done at once on a healthy disk).
const WAIT: Option<Duration> = Some(Duration::from_secs(10));

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/project-v1.json")
}

fn app(data_dir: &Path) -> StudioApp {
    let project = ServoProject { servos: vec![Servo::new(1, "左肩")], ..ServoProject::default() };
    let mut app = StudioApp::new(project, None, no_waker()).with_data_dir(data_dir.to_path_buf());
    // The recovery file is read off the frame: its offer is there once that read is done.
    app.finish_file_work(WAIT);
    app
}

fn harness(app: StudioApp) -> Harness<'static, StudioApp> {
    common::ui::window(app, (1200.0, 800.0))
}

#[test]
fn autosave_then_recovery_after_a_crash() {
    let data = tempfile::tempdir().unwrap();
    let mut first = app(data.path());
    first.apply(Action::family(servo_studio::ui::ServoAction::CapturePose { from_board: false }));
    assert!(first.document.dirty);
    first.autosave_if_due(Instant::now() + Duration::from_secs(1));
    first.finish_file_work(WAIT);
    assert!(!data.path().join("recovery.json").exists(), "not due yet");
    first.autosave_if_due(Instant::now() + Duration::from_secs(31));
    first.finish_file_work(WAIT);
    assert!(data.path().join("recovery.json").exists());
    let unsaved = first.document.project.servo.clone();
    drop(first); // the "crash": no save

    let mut harness = harness(app(data.path()));
    harness.run();
    assert!(harness.query_by_label("Recover unsaved work?").is_some());
    harness.get_by_label("Recover").click();
    harness.run();
    assert_eq!(harness.state().document.project.servo, unsaved);
    assert!(harness.state().document.dirty, "recovered work is unsaved until saved");

    // Saving clears the recovery file, so the next start offers nothing.
    let saved = data.path().join("saved.json");
    harness.state_mut().apply(Action::SaveAs(saved.clone()));
    harness.state_mut().finish_file_work(WAIT);
    assert!(!data.path().join("recovery.json").exists());
    assert_eq!(project::load(&saved).unwrap().servo, unsaved);
    assert!(app(data.path()).files.recovery_offer.is_none());
}

#[test]
fn declining_recovery_removes_it() {
    let data = tempfile::tempdir().unwrap();
    let mut first = app(data.path());
    first.apply(Action::family(servo_studio::ui::ServoAction::CapturePose { from_board: false }));
    first.apply(Action::Autosave);
    first.finish_file_work(WAIT);
    let mut harness = harness(app(data.path()));
    harness.run();
    harness.get_by_label("Discard").click();
    harness.run();
    assert!(harness.state().files.recovery_offer.is_none());
    harness.state_mut().finish_file_work(WAIT);
    assert!(!data.path().join("recovery.json").exists());
    assert!(harness.state().document.project.servo.actions.is_empty());
}

#[test]
fn opening_with_unsaved_changes_asks_first() {
    let data = tempfile::tempdir().unwrap();
    let mut start = app(data.path());
    start.apply(Action::family(servo_studio::ui::ServoAction::CapturePose { from_board: false }));
    let mut harness = harness(start);
    harness.run();
    harness.state_mut().apply(Action::Open(fixture()));
    harness.run();
    assert_eq!(harness.state().files.unsaved_prompt, Some(AfterUnsaved::Open(fixture())));
    assert!(harness.query_by_label("Unsaved changes").is_some());
    harness.get_by_label("Cancel").click();
    harness.run();
    assert_eq!(harness.state().document.project.servo.actions.len(), 1, "cancel keeps the work");

    harness.state_mut().apply(Action::Open(fixture()));
    harness.run();
    harness.get_by_label("Discard").click();
    harness.run();
    harness.state_mut().finish_file_work(WAIT);
    assert_eq!(harness.state().document.project.servo, project::load(&fixture()).unwrap().servo);
    assert_eq!(harness.state().document.path, Some(fixture()));
    assert!(!harness.state().document.dirty);
    assert_eq!(harness.state().files.recent, vec![fixture()]);
}

#[test]
fn save_in_the_question_saves_then_goes_on() {
    let data = tempfile::tempdir().unwrap();
    let path = data.path().join("mine.json");
    let mut start = app(data.path());
    start.apply(Action::SaveAs(path.clone()));
    start.finish_file_work(WAIT);
    start.apply(Action::family(servo_studio::ui::ServoAction::CapturePose { from_board: false }));
    let edited = start.document.project.servo.clone();
    let mut harness = harness(start);
    harness.run();
    harness.state_mut().apply(Action::NewProject);
    harness.run();
    harness.get_by_label("Save").click();
    harness.run();
    harness.state_mut().finish_file_work(WAIT);
    assert_eq!(project::load(&path).unwrap().servo, edited, "saved first");
    assert_eq!(harness.state().document.project.servo, ServoProject::default(), "then the new project");
}

#[test]
fn a_malformed_file_is_reported_not_opened() {
    let data = tempfile::tempdir().unwrap();
    let bad = data.path().join("bad.json");
    std::fs::write(&bad, "{\"format\": \"servo-studio-project\", \"servos\": [ }").unwrap();
    let mut app = app(data.path());
    let before = app.document.project.servo.clone();
    app.apply(Action::Open(bad));
    app.finish_file_work(WAIT);
    let status = app.status.clone().unwrap();
    assert!(status.is_error && status.text.contains("line 1, column"), "{}", status.text);
    assert_eq!(app.document.project.servo, before);
}

#[test]
fn a_file_with_a_misspelt_key_opens_and_says_what_was_ignored() {
    let data = tempfile::tempdir().unwrap();
    let misspelt = data.path().join("misspelt.json");
    let text = std::fs::read_to_string(fixture()).unwrap().replacen("\"min_deg\"", "\"min_degs\"", 1);
    std::fs::write(&misspelt, format!("\u{feff}{text}")).unwrap();
    let mut app = app(data.path());
    app.apply(Action::Open(misspelt.clone()));
    app.finish_file_work(WAIT);
    assert_eq!(app.document.path, Some(misspelt));
    let status = app.status.clone().unwrap();
    assert!(status.is_error, "shown as a warning: {}", status.text);
    assert!(
        status.text.contains("1 unknown key(s) ignored") && status.text.contains("servos[0].min_degs"),
        "{}",
        status.text
    );
}

#[derive(Debug)]
struct Dropped(PathBuf);

impl egui::DroppedFile for Dropped {
    fn path(&self) -> &Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|error| error.to_string())
    }
}

#[test]
fn a_dropped_project_file_opens() {
    let data = tempfile::tempdir().unwrap();
    let mut harness = harness(app(data.path()));
    harness.run();
    harness.input_mut().dropped_files.push(Arc::new(Dropped(fixture())));
    harness.run();
    harness.state_mut().finish_file_work(WAIT);
    assert_eq!(harness.state().document.path, Some(fixture()));
    assert_eq!(harness.state().document.project.servo.project_id, 20261121);
}

#[test]
fn remembered_settings_round_trip() {
    let data = tempfile::tempdir().unwrap();
    let mut first = app(data.path());
    first.apply(Action::Open(fixture()));
    first.finish_file_work(WAIT);
    first.apply(Action::SetLanguage(servo_studio::ui::Language::TraditionalChinese));
    first.apply(Action::ShowTab(servo_studio::ui::Tab::Board));
    let remembered = first.remembered();
    let text = serde_json::to_string(&remembered).unwrap();
    let mut second = app(data.path());
    second.restore(serde_json::from_str(&text).unwrap(), false);
    assert_eq!(second.remembered(), remembered);
    assert_eq!(second.files.recent, vec![fixture()]);
}

/// The family used last comes back with the tab, unless the project opened
/// (or the demo) brings its own; a tab of another family falls back to the
/// family's first. What an earlier version stored still reads.
#[test]
fn the_remembered_family_and_tab_are_restored() {
    use servo_studio::project::Family;
    use servo_studio::ui::{Remembered, Start, Tab};
    let stored = r#"{"recent":[],"language":"English","tab":"Motions","family":"plen2","plen2_pacing":"Safe"}"#;
    let remembered: Remembered = serde_json::from_str(stored).unwrap();
    let app = Start::default().into_app(no_waker(), Some(remembered.clone()));
    assert_eq!(app.document.project.family, Family::Plen2, "the family used last");
    assert_eq!(app.window.tab, Tab::Motions);
    assert_eq!(app.remembered().plen2_pacing, servo_studio::device::plen2::PacingMode::Safe);

    let from_file = Start { project: Some(project::Project::default()), ..Start::default() };
    let app = from_file.into_app(no_waker(), Some(remembered.clone()));
    assert_eq!(app.document.project.family, Family::Servo, "the file's family wins");
    assert_eq!(app.window.tab, Tab::Servos, "Motions is not a servo tab: the family's first");

    let mut app = StudioApp::new(project::Project::default(), None, no_waker());
    app.restore(Remembered { tab: "Log".into(), ..remembered }, false);
    assert_eq!((app.document.project.family, app.window.tab), (Family::Plen2, Tab::Log));
}

#[test]
fn a_recovery_file_that_is_a_named_pipe_neither_blocks_the_start_nor_is_read() {
    let data = tempfile::tempdir().unwrap();
    let fifo = data.path().join("recovery.json");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    // Read in the frame, a pipe nobody writes to would hold the editor's start for ever.
    let (started, start) = crossbeam_channel::bounded(1);
    let dir = data.path().to_path_buf();
    std::thread::spawn(move || {
        let offer = app(&dir).files.recovery_offer;
        let _ = started.send(offer.is_some());
    });
    let offered = start.recv_timeout(Duration::from_secs(10)).expect("the editor starts, the pipe refused at once");
    assert!(!offered, "a pipe is no recovery file");
}

/// A desktop with no file-dialog service (no desktop portal with a file
/// chooser, no zenity: a bare X session): File → Open… and Save as… use the
/// editor's own picker — said, with what to install — and what is chosen there
/// is opened, or saved where it was named.
#[test]
fn without_a_file_dialog_service_the_editors_own_picker_opens_and_saves() {
    let data = tempfile::tempdir().unwrap();
    let folder = tempfile::tempdir().unwrap();
    std::fs::copy(fixture(), folder.path().join("skull.json")).unwrap();
    let app = app(data.path()).with_own_file_picker("zenity");
    let mut harness = harness(app);
    harness.run();
    harness.get_by_label("File").click();
    harness.run();
    harness.get_by_label("Open…").click();
    harness.run();
    assert!(harness.state().asking_for_file(), "the editor's own picker is open");
    let said = harness.state().status.as_ref().map(|line| line.text.clone()).unwrap_or_default();
    assert!(said.contains("install zenity"), "said, with what to install: {said}");
    // Its folder typed, as a user does on a desktop with none of its own dialogs.
    harness.get_by_label("Folder").focus();
    harness.run();
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    harness.run();
    harness.get_by_label("Folder").type_text(&format!("{}", folder.path().display()));
    harness.run();
    harness.key_press(egui::Key::Enter);
    harness.run();
    harness.get_by_label("skull.json").click();
    harness.run();
    harness.get_by_label("Open").click();
    harness.run();
    harness.state_mut().finish_file_work(WAIT);
    harness.run();
    assert_eq!(harness.state().document.path.as_deref(), Some(folder.path().join("skull.json").as_path()));
    // Save as…: a new name in that folder.
    harness.get_by_label("File").click();
    harness.run();
    harness.get_by_label("Save As…").click();
    harness.run();
    harness.get_by_label("Name").focus();
    harness.run();
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    harness.run();
    harness.get_by_label("Name").type_text("copy.json");
    harness.run();
    harness.get_by_label("Save").click();
    harness.run();
    harness.state_mut().finish_file_work(WAIT);
    assert!(folder.path().join("copy.json").is_file(), "saved where it was named");
}
