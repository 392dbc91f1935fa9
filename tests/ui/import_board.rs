//! The import window previews what the board will play, not the file: a
//! Maestro frame too short for its channel's speed limit is cut short on the
//! figure and in the Now column, and the window says by how much; a map that
//! lands on a servo the project already has says so before Create; every word
//! of the window, its notes included, is in the interface's language.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use egui::accesskit::Role;
use egui_kittest::kittest::{NodeT, Queryable, by};
use servo_studio::interchange::build::{self, Options};
use servo_studio::interchange::{JointMap, text};
use servo_studio::project::{Family, Project, ServoProject};
use servo_studio::ui::import::{ImportAction, note, words};
use servo_studio::ui::{Action, Language, Tab};

use crate::common;

/// Channel 0 at speed 16 (¼ µs per 10 ms): +30° is 1200 ¼ µs, 75 updates,
/// but its frame lasts 500 ms, so the Maestro gets it to +20° before the
/// next frame (Pololu's rule: the next frame starts on time, arrived or not).
const CUT: &str = r#"<!--Pololu Maestro servo controller settings file, http://www.pololu.com/catalog/product/1350-->
<UscSettings version="1">
  <Channels ServosAvailable="6" ServoPeriod="156">
    <Channel name="arm" mode="Servo" min="3968" max="8000" homemode="Goto" home="6000" speed="16" acceleration="0" neutral="6000" range="1905" />
    <Channel name="" mode="Output" min="3968" max="8000" homemode="Off" home="3968" speed="0" acceleration="0" neutral="6000" range="1905" />
  </Channels>
  <Sequences>
    <Sequence name="reach">
      <Frame name="Frame 0" duration="500">7200 0</Frame>
      <Frame name="Frame 1" duration="1000">7200 0</Frame>
    </Sequence>
  </Sequences>
  <Script ScriptDone="true"></Script>
</UscSettings>"#;

fn open(language: Language, project: Project) -> egui_kittest::Harness<'static, servo_studio::ui::StudioApp> {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("reach.xml");
    std::fs::write(&file, CUT).unwrap();
    let mut app = common::ui::editor(project);
    app.apply(Action::SetLanguage(language));
    app.apply(Action::Import(ImportAction::Read(file)));
    let mut harness = common::ui::showing(app, Tab::Servos, (1280.0, 800.0));
    common::ui::run_until(&mut harness, "the board's playback worked out", |app| app.desks.import.board_known());
    // The tempdir may go: the file was read.
    drop(dir);
    harness
}

fn a_project_with_servo_0() -> Project {
    let mut project = ServoProject::default();
    project.servos.push(servo_studio::project::Servo::new(0, "mine"));
    Project::servo(project)
}

#[test]
fn the_preview_plays_the_move_the_speed_limit_cuts_short_and_says_by_how_much() {
    let mut harness = open(Language::English, Project::servo(ServoProject::default()));
    harness.state_mut().desks.import.session.as_mut().unwrap().time_ms = 500.0;
    harness.run();
    assert!(harness.query_by_label("20.0").is_some(), "the board has the arm at +20° when the frame ends");
    assert!(harness.query_by_label("30.0").is_none(), "not the file's +30°");
    let said = harness
        .get_by_label_contains("The board plays channel 0 (servo 0) up to")
        .accesskit_node()
        .label()
        .or_else(|| harness.get_by_label_contains("The board plays channel 0").accesskit_node().value())
        .unwrap_or_default();
    // 10° short as the frame ends; the arm goes on at its speed limit in the
    // next frame, so matched within half an update (5 ms) of it: 9.8°.
    assert!(said.contains("up to 9.8° from the file (at 0.50 s)"), "{said}");
    assert!(harness.query_by_label_contains("Maestro frame shorter than a channel's speed limit").is_some());
}

#[test]
fn a_map_onto_a_servo_the_project_has_is_said_before_create() {
    let harness = open(Language::English, a_project_with_servo_0());
    assert!(harness.query_by_label_contains("Channel 0 drives servo 0, which this project already has").is_some());
}

#[test]
fn the_window_and_its_notes_are_in_traditional_chinese() {
    let mut harness = open(Language::TraditionalChinese, a_project_with_servo_0());
    assert!(harness.query_all(by().role(Role::ComboBox).value("伺服機 0")).next().is_some());
    assert!(harness.query_by_label("匯入此專案的 伺服板").is_some());
    assert!(harness.query_by_label("reach.xml — Maestro 設定檔").is_some());
    assert!(harness.query_by_label_contains("通道 0 驅動的伺服機 0已在此專案中").is_some());
    assert!(harness.query_by_label_contains("開發板播放的通道 0（伺服機 0）與檔案最多相差").is_some());
    assert!(harness.query_by_label_contains("Maestro 影格短於通道速度限制所需").is_some());
    assert!(harness.query_by_label_contains("通道 1（Output）：不是伺服機").is_some());
    harness.state_mut().desks.import.session.as_mut().unwrap().time_ms = 0.0;
    harness.run();
    assert!(harness.query_by_label_contains("Channel").is_none(), "no English caption left");
}

/// Every note and error the conversions of every fixture say: each has its Chinese.
#[test]
fn every_note_a_conversion_says_has_its_traditional_chinese() {
    let chinese = words(Language::TraditionalChinese);
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/interchange");
    let mut said: Vec<String> = Vec::new();
    let mut texts: Vec<Vec<u8>> =
        vec![CUT.as_bytes().to_vec(), crate::interchange::maestro::SETTINGS.as_bytes().to_vec()];
    for folder in ["blender", "roboplus", "rplus", "maestro"] {
        for entry in std::fs::read_dir(dir.join(folder)).unwrap() {
            let path = entry.unwrap().path();
            if !path.to_string_lossy().contains("cut-short") {
                texts.push(std::fs::read(path).unwrap());
            }
        }
    }
    for bytes in &texts {
        let source =
            servo_studio::interchange::read_decoded(None, &text::decode(bytes.as_slice()).unwrap()).unwrap().unwrap();
        said.extend(source.dropped.iter().chain(&source.notes).cloned());
        for family in [Family::Servo, Family::Plen2] {
            let map = JointMap::for_source(&source, family, None);
            match build::build(&source, &map, &Options::new(family)) {
                Ok(built) => {
                    let report = built.report;
                    said.extend(report.converted.into_iter().chain(report.approximated).chain(report.dropped));
                }
                Err(error) => said.push(error.to_string()),
            }
        }
    }
    said.sort();
    said.dedup();
    assert!(said.len() >= 30, "{said:?}");
    let untranslated: Vec<&String> = said.iter().filter(|line| note(line, chinese) == **line).collect();
    assert!(untranslated.is_empty(), "notes with no Traditional Chinese: {untranslated:#?}");
}

/// Several channels landing on servos the project has are one warning with
/// their count, the list under it on demand; one is said on its own.
#[test]
fn channels_landing_on_servos_the_project_has_are_one_line_with_a_list_on_demand() {
    let maestro = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/interchange/maestro/mini-maestro-24-script.xml");
    let servos = (0..24).map(|id| servo_studio::project::Servo::new(id, format!("s{id}"))).collect();
    let mut app = common::ui::editor(Project::servo(ServoProject { servos, ..ServoProject::default() }));
    app.apply(Action::Import(ImportAction::Read(maestro)));
    let mut harness = common::ui::showing(app, Tab::Servos, (1280.0, 800.0));
    common::ui::run_until(&mut harness, "the file read", |app| app.desks.import.board_known());
    let landed = harness
        .state()
        .desks
        .import
        .session
        .as_ref()
        .unwrap()
        .map
        .entries
        .iter()
        .filter(|e| e.target.is_some())
        .count();
    assert!(landed > 1, "the fixture maps several channels: {landed}");
    let line = format!("{landed} channels drive servos this project already has");
    assert_eq!(harness.query_all_by_label_contains(&line).count(), 1, "one line: {line}");
    assert!(
        harness.query_by_label_contains("which this project already has: its limits").is_none(),
        "not one a channel"
    );
    assert_eq!(harness.query_all_by_label_contains(" → servo ").count(), 0, "the list folded away");
    harness.get_by_label(&format!("Which {landed} channels")).click();
    harness.run();
    assert_eq!(harness.query_all_by_label_contains(" → servo ").count(), landed, "the list, on demand");
}
