//! STOP is always on top and whole, and stops everything: with every window
//! and dialog of the editor open at once — import, export, the show, remote
//! control, the unsaved-changes question, the editor's own file picker — at
//! 1280×800, in each of the four languages, the language switched while they
//! are open, STOP's whole rectangle is STOP's (nothing drawn over any of it),
//! and a real pointer click on it stops the board. It stops the editor's own
//! preview too, and until Resume nothing that moves a robot goes out: it is
//! refused and said.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::link::LinkEvent;
use servo_studio::protocol::servo::Message;
use servo_studio::sim::SimEvent;
use servo_studio::ui::import::ImportAction;
use servo_studio::ui::show::ShowAction;
use servo_studio::ui::sound::SoundAction;
use servo_studio::ui::{Action, FileRequest, Language, ServoAction, ServoBoardLink, StudioApp, Tab};

const SIZE: (f32, f32) = (1280.0, 800.0);

/// The editor on the sample robot and the demo board, with every window open.
fn everything_open(language: Language) -> Harness<'static, StudioApp> {
    let mut app = common::ui::editor(servo_studio::ui::sample_project()).with_own_file_picker("zenity");
    app.apply(Action::SetLanguage(language));
    app.apply(Action::ConnectDemo);
    let maestro = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/interchange/maestro/mini-maestro-24-script.xml");
    app.apply(Action::Import(ImportAction::Read(maestro)));
    app.apply(Action::Import(ImportAction::OpenExport));
    app.apply(Action::Show(ShowAction::OpenProject));
    app.apply(Action::Show(ShowAction::RemoteWindow));
    app.apply(Action::AskFile(FileRequest::Open));
    // Unsaved changes, then New: the question.
    app.apply(Action::SetLiveSpeed(90.0));
    let mut servo = app.document.project.servo.clone();
    servo.servos[0].caption.push('!');
    app.apply(Action::Edit { edit: servo_studio::project::Edit::ReplaceAll(Box::new(servo)), coalesce: None });
    app.apply(Action::NewProject);
    // A sound, read, and Follow the sound open on it.
    let clicks = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/sound/clicks.flac");
    app.apply(Action::Sound(SoundAction::Add(clicks)));
    let mut harness = common::ui::showing(app, Tab::Servos, SIZE);
    common::ui::run_until(&mut harness, "the import window read its file", |app| !app.desks.import.busy());
    common::ui::run_until(&mut harness, "the sound read", |app| {
        app.document.project.sound.as_ref().is_some_and(|track| !track.sha256.is_empty())
    });
    harness.state_mut().apply(Action::Sound(SoundAction::OpenFollow));
    // Work autosaved by a session that ended badly: the recovery question (once the start's own look found none).
    harness.state_mut().finish_file_work(Some(std::time::Duration::from_secs(10)));
    harness.state_mut().files.recovery_offer = Some(servo_studio::ui::files::Recovery {
        path: None,
        saved_at: "12:00".into(),
        project: servo_studio::ui::sample_project(),
    });
    harness.run_steps(3);
    harness
}

/// STOP's whole rectangle is STOP's: at its corners and centre nothing else is on top.
fn stop_whole_and_on_top(harness: &Harness<'static, StudioApp>, said: &str) -> egui::Rect {
    let rect = harness.state().stop_rect().expect("STOP was drawn");
    assert!(rect.min.x >= 0.0 && rect.max.x <= SIZE.0 && rect.min.y >= 0.0, "{said}: STOP inside the window: {rect:?}");
    let stop = egui::LayerId::new(egui::Order::Tooltip, egui::Id::unique("STOP"));
    let inset = rect.shrink(2.0);
    for point in [inset.left_top(), inset.right_top(), inset.left_bottom(), inset.right_bottom(), inset.center()] {
        assert_eq!(harness.ctx.layer_id_at(point), Some(stop), "{said}: something covers STOP at {point:?}");
    }
    rect
}

/// A real pointer click (pressed and released there), not an accessibility action.
fn click_at(harness: &mut Harness<'static, StudioApp>, at: egui::Pos2) {
    harness.drag_at(at);
    harness.step();
    harness.drop_at(at);
    harness.step();
    harness.run_steps(2);
}

#[test]
fn with_every_window_open_in_every_language_stop_is_whole_on_top_and_clicks() {
    for language in Language::ALL {
        let mut harness = everything_open(language);
        for title in [
            "import.title",
            "import.export_title",
            "show.title",
            "show.remote_title",
            "strings.unsaved_title",
            "strings.recover_title",
            "follow.title",
            "browser.title_open",
        ] {
            let title = language.word(title);
            assert!(harness.query_all_by_label(title).next().is_some(), "{language:?}: {title} is open");
        }
        stop_whole_and_on_top(&harness, &format!("{language:?}"));
        // Switched with everything open: windows widen, STOP stays whole.
        for other in Language::ALL {
            harness.state_mut().apply(Action::SetLanguage(other));
            harness.run_steps(3);
            stop_whole_and_on_top(&harness, &format!("{language:?} switched to {other:?}"));
        }
        harness.state_mut().apply(Action::SetLanguage(language));
        harness.run_steps(3);
        let rect = stop_whole_and_on_top(&harness, &format!("{language:?} again"));
        click_at(&mut harness, rect.right_bottom() - egui::vec2(6.0, 6.0));
        assert!(harness.state().stopped(), "{language:?}: the click stopped everything");
    }
}

#[test]
fn stop_stops_the_editors_own_preview_and_nothing_moves_until_resume() {
    let mut app = common::ui::editor(servo_studio::ui::sample_project());
    app.apply(Action::ConnectDemo);
    let mut harness = common::ui::showing(app, Tab::Actions, SIZE);
    // The action editor's preview plays (Space), looping.
    harness.key_press(egui::Key::Space);
    harness.run_steps(3);
    assert!(common::ui::servo_ui(harness.state()).figure.transport.is_playing(), "the preview plays");
    harness.state_mut().apply(Action::Stop);
    harness.run_steps(3);
    assert!(!common::ui::servo_ui(harness.state()).figure.transport.is_playing(), "STOP stopped the preview");
    assert!(harness.state().stopped());
    // Run on board, a slider, a played action: each refused and said; the board is sent none of them.
    let requester = common::ui::servo_board(harness.state()).unwrap().requester();
    let handled = |harness: &Harness<'static, StudioApp>| -> Vec<Message> {
        let link = harness.state().link.as_ref().unwrap();
        link.demo_board()
            .unwrap()
            .events()
            .try_iter()
            .filter_map(|event| match event {
                LinkEvent::Driver(SimEvent::Handled(message)) => Some(message),
                _ => None,
            })
            .collect()
    };
    handled(&harness);
    let macro_id = harness.state().document.project.servo.macros[0].id;
    let action_id = harness.state().document.project.servo.actions[0].id;
    for refused in [
        ServoAction::RunMacro(macro_id),
        ServoAction::PlayAction(action_id),
        ServoAction::SetPose { servo_id: 1, degree: 40 },
    ] {
        harness.state_mut().apply(Action::family(refused.clone()));
        harness.run_steps(2);
        let said = harness.state().status.as_ref().map(|line| line.text.clone()).unwrap_or_default();
        assert!(said.contains("press Resume"), "{refused:?}: {said}");
    }
    // A question answered after them: whatever was sent before it has been handled.
    requester.query_servos(255).unwrap();
    let moves: Vec<Message> = handled(&harness)
        .into_iter()
        .filter(|message| matches!(message, Message::ExecuteMacroRequest { .. } | Message::ExecuteActionRequest { .. }))
        .collect();
    assert_eq!(moves, Vec::<Message>::new(), "nothing that moves went out");
    assert!(harness.query_by_label("Resume").is_some(), "Resume beside STOP while it holds");
    harness.get_by_label("Resume").click();
    harness.run_steps(3);
    assert!(!harness.state().stopped());
    assert!(harness.query_by_label("Resume").is_none(), "gone once resumed");
    harness.state_mut().apply(Action::family(ServoAction::SetPose { servo_id: 1, degree: 40 }));
    harness.run_steps(2);
    common::ui::servos_until(&requester, "servo 1 to 40° once resumed", |servos| {
        servos.iter().any(|servo| servo.servo_id == 1 && servo.angle == 40)
    });
}
