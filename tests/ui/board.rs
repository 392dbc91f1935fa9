//! The board panel, driven through egui_kittest against the in-process
//! emulated board: upload with backup and verification, a refused item, and
//! the end-to-end compose → upload → read back round trip.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::device::servo::ServoImage;
use servo_studio::link::no_waker;
use servo_studio::project::{Project, Servo, ServoProject};
use servo_studio::sim::{Faults, SimConfig};
use servo_studio::ui::{Action, BoardResult, ServoAction, StudioApp, Worded, servo_demo_link};

fn harness(app: StudioApp) -> Harness<'static, StudioApp> {
    common::ui::window(app, (1200.0, 800.0))
}

use common::ui::run_until;

/// A few frames: the app keeps repainting while a board is connected, so it never "settles".
fn frames(harness: &mut Harness<'static, StudioApp>) {
    harness.run_steps(3);
}

/// The last result's failure or problems, as the panel words them.
fn shown_error(app: &StudioApp) -> String {
    let result = common::ui::servo_ui(app).board_result.as_ref().expect("a result");
    result.error_text(app.language).unwrap_or_else(|| panic!("expected a failure, got {result:?}"))
}

/// The pending comparison's differences, as the panel words them.
fn shown_differences(app: &StudioApp) -> Vec<String> {
    let pending = common::ui::servo_ui(app).pending.as_ref().expect("a comparison");
    let differences = pending.differences.as_ref().expect("the project fits in board records");
    differences.iter().map(|difference| difference.worded(app.language)).collect()
}

fn servos_only() -> ServoProject {
    let mut left = Servo::new(1, "左肩");
    left.min_deg = -90;
    left.max_deg = 90;
    left.home_deg = 5;
    ServoProject { project_id: 42, servos: vec![left, Servo::new(2, "右肩")], ..ServoProject::default() }
}

/// An app with a composed project (two captured poses) connected to a demo board
/// that starts out holding `board`.
fn composed(board: &ServoProject, config: SimConfig, data_dir: &std::path::Path) -> Harness<'static, StudioApp> {
    let mut app = StudioApp::new(servos_only(), None, no_waker()).with_data_dir(data_dir.to_path_buf());
    app.link = Some(servo_demo_link(&Project::servo(board.clone()), config, no_waker()).unwrap());
    let mut harness = harness(app);
    frames(&mut harness);
    // Compose through the UI: two poses.
    harness.state_mut().apply(Action::family(ServoAction::SetPose { servo_id: 1, degree: -40 }));
    harness.get_by_label("Capture pose").click();
    frames(&mut harness);
    harness.state_mut().apply(Action::family(ServoAction::SetPose { servo_id: 2, degree: 25 }));
    harness.get_by_label("Capture pose").click();
    frames(&mut harness);
    assert_eq!(harness.state().document.project.servo.actions.len(), 2);
    harness.get_by_label("Board").click();
    frames(&mut harness);
    harness
}

#[test]
fn upload_then_read_back_round_trips_and_keeps_a_backup() {
    let data = tempfile::tempdir().unwrap();
    let previous = ServoProject { project_id: 9, ..ServoProject::default() };
    let mut harness = composed(&previous, SimConfig::default(), data.path());
    let composed_project = harness.state().document.project.servo.clone();

    harness.get_by_label("Upload to board").click();
    frames(&mut harness);
    run_until(&mut harness, "the comparison", |app| common::ui::servo_ui(app).pending.is_some());
    let differences = shown_differences(harness.state());
    assert!(differences.iter().any(|d| d.contains("project id")), "{differences:?}");
    harness.get_by_label("Back up the board, then overwrite it").click();
    frames(&mut harness);
    run_until(&mut harness, "the upload", |app| common::ui::servo_ui(app).board_result.is_some());
    match common::ui::servo_ui(harness.state()).board_result.clone().unwrap() {
        BoardResult::Uploaded { items, backup, .. } => {
            // clear, project id, servo parameters, 2 actions
            assert_eq!(items.len(), 5, "{items:?}");
            assert!(items.iter().any(|item| item.to_string().starts_with("action 2")), "{items:?}");
            let backup = backup.unwrap();
            assert!(backup.starts_with(data.path().join("backups")));
            assert_eq!(servo_studio::project::load(&backup).unwrap().servo, previous);
        }
        other => panic!("expected an upload, got {other:?}"),
    }
    assert!(
        harness.query_all_by_label_contains("Uploaded and verified, items: 5").count() >= 2,
        "the panel and the status line"
    );

    // Read it back: identical, and the project is replaced by what the board holds.
    harness.get_by_label("Read board into project").click();
    frames(&mut harness);
    run_until(&mut harness, "the comparison", |app| common::ui::servo_ui(app).pending.is_some());
    assert_eq!(shown_differences(harness.state()), Vec::<String>::new());
    assert!(harness.query_by_label("The board already holds exactly this project.").is_some());
    harness.get_by_label("Replace the project with the board").click();
    frames(&mut harness);
    let read_back = harness.state().document.project.servo.clone();
    assert_eq!(ServoImage::from_project(&read_back).unwrap(), ServoImage::from_project(&composed_project).unwrap());
    // The client-side limits, which the board does not store, are kept: the
    // project read back is exactly the one composed.
    assert_eq!(read_back, composed_project);
}

#[test]
fn an_upload_with_a_refused_item_shows_that_items_error() {
    let data = tempfile::tempdir().unwrap();
    let config = SimConfig { faults: Faults { refuse_add: vec![2], ..Faults::default() }, ..SimConfig::default() };
    let mut harness = composed(&ServoProject::default(), config, data.path());
    harness.get_by_label("Upload to board").click();
    frames(&mut harness);
    run_until(&mut harness, "the comparison", |app| common::ui::servo_ui(app).pending.is_some());
    harness.get_by_label("Back up the board, then overwrite it").click();
    frames(&mut harness);
    run_until(&mut harness, "the upload", |app| common::ui::servo_ui(app).board_result.is_some());
    let error = shown_error(harness.state());
    assert!(error.contains("action 2 \"Pose 2\": the board refused it"), "{error}");
    match common::ui::servo_ui(harness.state()).board_result.clone().unwrap() {
        BoardResult::Failed { items, .. } => {
            assert!(
                items.iter().any(|item| item.to_string().starts_with("action 1")),
                "action 1 was written: {items:?}"
            );
        }
        other => panic!("expected a failure, got {other:?}"),
    }
    assert!(
        harness.query_all_by_label_contains("action 2 \"Pose 2\": the board refused it").count() >= 2,
        "the panel and the status line"
    );
}

#[test]
fn an_invalid_project_is_not_uploaded() {
    let data = tempfile::tempdir().unwrap();
    let mut harness = composed(&ServoProject::default(), SimConfig::default(), data.path());
    let mut broken = harness.state().document.project.servo.clone();
    broken.actions[0].steps[0].servo_id = 77;
    harness
        .state_mut()
        .apply(Action::Edit { edit: servo_studio::project::Edit::ReplaceAll(Box::new(broken)), coalesce: None });
    harness.get_by_label("Upload to board").click();
    frames(&mut harness);
    assert!(harness.state().operation.is_none(), "no board operation starts");
    assert!(matches!(common::ui::servo_ui(harness.state()).board_result, Some(BoardResult::Invalid { .. })));
    let error = shown_error(harness.state());
    assert!(error.contains("servo 77 does not exist"), "{error}");
    assert!(harness.query_all_by_label_contains("servo 77 does not exist").count() >= 1, "the panel shows it");
    assert!(harness.query_by_label("Upload anyway").is_some(), "the user may restore it as it is");
}

#[test]
fn the_board_panel_speaks_traditional_chinese() {
    let data = tempfile::tempdir().unwrap();
    let mut harness = composed(&ServoProject::default(), SimConfig::default(), data.path());
    harness.state_mut().apply(Action::SetLanguage(servo_studio::ui::Language::TraditionalChinese));
    frames(&mut harness);
    for caption in ["上傳至控制板", "讀取控制板至專案", "匯出控制板至檔案…"] {
        assert!(harness.query_by_label(caption).is_some(), "{caption}");
    }
}

#[test]
fn a_refused_item_is_named_in_traditional_chinese() {
    let data = tempfile::tempdir().unwrap();
    let config = SimConfig { faults: Faults { refuse_add: vec![2], ..Faults::default() }, ..SimConfig::default() };
    let mut harness = composed(&ServoProject::default(), config, data.path());
    harness.state_mut().apply(Action::SetLanguage(servo_studio::ui::Language::TraditionalChinese));
    frames(&mut harness);
    harness.get_by_label("上傳至控制板").click();
    frames(&mut harness);
    run_until(&mut harness, "the comparison", |app| common::ui::servo_ui(app).pending.is_some());
    let differences = shown_differences(harness.state());
    assert!(differences.iter().any(|d| d == "動作 1：控制板上沒有"), "{differences:?}");
    harness.get_by_label("備份控制板後覆寫").click();
    frames(&mut harness);
    run_until(&mut harness, "the upload", |app| common::ui::servo_ui(app).board_result.is_some());
    let error = shown_error(harness.state());
    assert!(error.starts_with("動作 2 \"Pose 2\"：控制板拒絕了"), "{error}");
    assert!(harness.query_all_by_label_contains("控制板拒絕了").count() >= 2, "the panel and the status line");
    match common::ui::servo_ui(harness.state()).board_result.clone().unwrap() {
        BoardResult::Failed { items, .. } => {
            let language = servo_studio::ui::Language::TraditionalChinese;
            assert!(items.iter().any(|item| item.worded(language).starts_with("動作 1")), "{items:?}");
        }
        other => panic!("expected a failure, got {other:?}"),
    }
}

#[test]
fn an_invalid_project_is_explained_in_traditional_chinese() {
    let data = tempfile::tempdir().unwrap();
    let mut harness = composed(&ServoProject::default(), SimConfig::default(), data.path());
    let mut broken = harness.state().document.project.servo.clone();
    broken.actions[0].steps[0].servo_id = 77;
    harness
        .state_mut()
        .apply(Action::Edit { edit: servo_studio::project::Edit::ReplaceAll(Box::new(broken)), coalesce: None });
    harness.state_mut().apply(Action::SetLanguage(servo_studio::ui::Language::TraditionalChinese));
    harness.state_mut().apply(Action::family(ServoAction::BoardCompare(servo_studio::ui::BoardIntent::Upload)));
    assert!(matches!(common::ui::servo_ui(harness.state()).board_result, Some(BoardResult::Invalid { .. })));
    let error = shown_error(harness.state());
    assert!(error.contains("動作 1 \"Pose 1\"，步驟 1：舵機 77 不存在"), "{error}");
    assert!(error.starts_with("專案有 1 個錯誤"), "{error}");
}

#[test]
fn upload_anyway_restores_a_board_image_with_authoring_problems_exactly() {
    let data = tempfile::tempdir().unwrap();
    let image = common::unauthorable_image();
    // A backup of a board another tool wrote, opened as the project.
    let mut app = StudioApp::new(image.to_project(), None, no_waker()).with_data_dir(data.path().to_path_buf());
    app.link = Some(servo_demo_link(&Project::default(), SimConfig::default(), no_waker()).unwrap());
    app.apply(Action::ShowTab(servo_studio::ui::Tab::Board));
    let mut harness = harness(app);
    // Wait for the board's status, so the bar's text no longer changes under the pointer.
    run_until(&mut harness, "the board's status", |app| {
        common::ui::servo_board(app).is_some_and(|servo| servo.memory.is_some())
    });
    harness.get_by_label("Upload to board").click();
    frames(&mut harness);
    assert!(matches!(common::ui::servo_ui(harness.state()).board_result, Some(BoardResult::Invalid { .. })));
    let error = shown_error(harness.state());
    assert!(error.contains("servo 1 already has a step in this action"), "{error}");
    assert!(error.contains("macro 999 does not exist"), "{error}");
    assert!(harness.state().operation.is_none(), "nothing starts until the user says so");
    harness.get_by_label("Upload anyway").click();
    frames(&mut harness);
    run_until(&mut harness, "the comparison", |app| common::ui::servo_ui(app).pending.is_some());
    harness.get_by_label("Back up the board, then overwrite it").click();
    frames(&mut harness);
    run_until(&mut harness, "the upload", |app| {
        common::ui::servo_ui(app).board_result.is_some() && app.operation.is_none()
    });
    assert!(
        matches!(common::ui::servo_ui(harness.state()).board_result, Some(BoardResult::Uploaded { .. })),
        "{:?}",
        common::ui::servo_ui(harness.state()).board_result
    );
    let requester = common::ui::servo_board(harness.state()).unwrap().requester();
    let board =
        servo_studio::device::servo::read_image(&requester, &mut |_| {}, &servo_studio::device::Cancel::never())
            .unwrap();
    assert_eq!(common::record_bytes(&board), common::record_bytes(&image), "the board holds the image byte for byte");
}

/// The editor asked to end (Ctrl-C in its terminal) in the middle of an
/// upload: the upload stops between two requests, and what it left — the
/// items that reached the board, the backup — is said, not lost with the window.
#[test]
fn ending_the_editor_mid_upload_stops_it_at_a_safe_point_and_says_what_it_left() {
    let data = tempfile::tempdir().unwrap();
    // A slow line: the upload is still writing when the signal comes.
    let config = SimConfig { baud: Some(9_600), ..SimConfig::default() };
    let mut harness = composed(&ServoProject { project_id: 9, ..ServoProject::default() }, config, data.path());
    let (terminate, terminated) = crossbeam_channel::bounded(1);
    harness.state_mut().terminate_on(terminated);
    harness.get_by_label("Upload to board").click();
    frames(&mut harness);
    run_until(&mut harness, "the comparison", |app| common::ui::servo_ui(app).pending.is_some());
    harness.get_by_label("Back up the board, then overwrite it").click();
    run_until(&mut harness, "the first write", |app| {
        let running = app.operation.as_ref().and_then(|running| running.get::<servo_studio::ui::ServoOperation>());
        running
            .and_then(|operation| operation.progress.as_ref())
            .is_some_and(|step| step.phase == servo_studio::device::Phase::Write)
    });
    terminate.send(()).unwrap();
    harness.step();
    let app = harness.state();
    assert!(app.operation.is_none(), "the upload ended before the window");
    assert!(app.link.is_none(), "the link is closed");
    let text = common::ui::servo_ui(app)
        .board_result
        .as_ref()
        .and_then(|result| result.error_text(app.language))
        .expect("a failure");
    assert!(text.contains("cancelled") && text.contains("reached"), "what reached the board is said: {text}");
    assert!(text.contains(&data.path().join("backups").display().to_string()), "the backup is named: {text}");
}
