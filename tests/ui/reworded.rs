//! A language chosen while messages show says them again in that language:
//! the status line and the show's run log hold what they mean, not the words
//! they were first said in. With the editor in Japanese, a board connected,
//! a file read into the import window, the show window open on the project
//! and a Play that could not reach its board said in its log, switching to
//! Korean leaves no kana anywhere in the window, and switching on to English
//! leaves no Hangul.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable, by};
use servo_studio::ui::import::ImportAction;
use servo_studio::ui::show::ShowAction;
use servo_studio::ui::{Action, Language, StudioApp, Tab};

/// Every text the window shows (labels, buttons, fields), with what it is.
fn texts(harness: &Harness<'static, StudioApp>) -> Vec<String> {
    harness
        .query_all(by().predicate(|node| node.label().is_some() || node.value().is_some()))
        .map(|node| {
            let node = node.accesskit_node();
            let text = [node.label(), node.value()].into_iter().flatten().collect::<Vec<_>>().join(" | ");
            format!("{:?}: {text}", node.role())
        })
        .collect()
}

fn is_kana(c: char) -> bool {
    ('\u{3041}'..='\u{30ff}').contains(&c)
}

fn is_hangul(c: char) -> bool {
    ('\u{ac00}'..='\u{d7a3}').contains(&c) || ('\u{3131}'..='\u{318e}').contains(&c)
}

/// The texts written in `script` (none, when the window says nothing left over).
fn left_over(harness: &Harness<'static, StudioApp>, script: fn(char) -> bool) -> Vec<String> {
    texts(harness).into_iter().filter(|text| text.chars().any(script)).collect()
}

#[test]
fn switching_the_language_says_every_message_showing_again_in_the_new_one() {
    let mut app = common::ui::editor(servo_studio::ui::sample_project());
    app.apply(Action::SetLanguage(Language::Japanese));
    app.apply(Action::ConnectDemo);
    let maestro = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/interchange/maestro/mini-maestro-24-script.xml");
    app.apply(Action::Import(ImportAction::Read(maestro)));
    app.apply(Action::Show(ShowAction::OpenProject));
    // The project's device has no port: Play says so in the run log.
    app.apply(Action::Show(ShowAction::Play));
    let mut harness = common::ui::showing(app, Tab::Servos, (1280.0, 800.0));
    common::ui::run_until(&mut harness, "the import window read its file", |app| !app.desks.import.busy());
    common::ui::run_until(&mut harness, "the show's run log said why it did not play", |app| {
        app.desks.show.session.as_ref().is_some_and(|session| !session.said.is_empty())
    });
    let status = harness.state().status.clone().expect("connecting said so");
    assert!(status.text.chars().any(is_kana), "the status line is Japanese first: {}", status.text);
    let log = harness.state().desks.show.session.as_ref().unwrap().said[0].in_(Language::Japanese).to_string();
    assert!(log.contains("ポート"), "the run log says the port is missing, in Japanese: {log}");
    assert!(!left_over(&harness, is_kana).is_empty(), "the window is in Japanese to begin with");
    assert!(harness.query_all_by_label_contains(&log).next().is_some(), "the run log shows its line: {log}");

    harness.state_mut().apply(Action::SetLanguage(Language::Korean));
    harness.run_steps(3);
    assert_eq!(left_over(&harness, is_kana), Vec::<String>::new(), "Japanese left showing after switching to Korean");
    let status = harness.state().status.clone().unwrap();
    assert!(status.text.chars().any(is_hangul), "the status line says it in Korean: {}", status.text);
    assert!(harness.query_all_by_label_contains("포트").next().is_some(), "the run log's line, in Korean");

    harness.state_mut().apply(Action::SetLanguage(Language::English));
    harness.run_steps(3);
    assert_eq!(left_over(&harness, is_hangul), Vec::<String>::new(), "Korean left showing after switching to English");
    assert!(harness.query_all_by_label_contains("no port").next().is_some(), "the run log's line, in English");
}
