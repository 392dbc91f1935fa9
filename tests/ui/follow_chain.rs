//! Follow the sound on a full PLEN2: the official motions fill all 90 slots.
//! The dialog says so and asks for a slot; the slot picked (and those after
//! it, as many as the sound needs) are replaced by a chain of motions of up
//! to 20 frames, each jumping to the next, in one undo step; the robot plays
//! the chain as long as the sound, and the frames' strip shows the chain as
//! one. A fit that cannot be made is said in degrees, in 繁體中文 too.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use crate::common;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{Queryable, by};
use servo_studio::device::plen2::playback::{self, StoredMotions};
use servo_studio::link::no_waker;
use servo_studio::project::plen2::{MAX_FRAMES, Motion};
use servo_studio::project::{Family, Project, SoundTrack};
use servo_studio::ui::{Action, Language, StudioApp, Tab};

/// Where the chain is written from: a slot the motions list shows.
const FIRST: u8 = 2;

/// The sound's length, ms: a talker, far longer than one motion holds.
const SOUND_MS: u32 = 20_000;

/// A talker: bursts of a buzz 150–400 ms long, 80–300 ms apart, at 8 kHz.
fn talk(path: &Path) {
    let rate = 8_000u32;
    let mut samples = Vec::new();
    let mut walk = 7_u32;
    while samples.len() < (SOUND_MS * rate / 1000) as usize {
        walk = walk.wrapping_mul(1_103_515_245).wrapping_add(12_345);
        let (on, off) = (150 + (walk >> 8) % 250, 80 + (walk >> 20) % 220);
        let start = samples.len();
        samples.extend((0..on * rate / 1000).map(|i| ((start + i as usize) as f32 * 0.11).sin() * 0.7));
        samples.extend((0..off * rate / 1000).map(|_| 0.0));
    }
    samples.truncate((SOUND_MS * rate / 1000) as usize);
    std::fs::write(path, servo_studio::audio::pcm16_wav(&samples, rate, 1)).unwrap();
}

/// The 90 official motions and the talker's sound, saved in `dir`, open on Motions.
fn full_robot(dir: &Path, language: Language) -> Option<Harness<'static, StudioApp>> {
    let files = common::official_motion_files()?;
    let mut project = Project::empty(Family::Plen2);
    project.plen2.motions =
        files.iter().map(|file| servo_studio::project::motion_json::read_motion_file(file).unwrap().0).collect();
    assert_eq!(project.plen2.motions.len(), 90, "every slot taken");
    let sound = dir.join("talk.wav");
    talk(&sound);
    project.sound = Some(SoundTrack {
        path: "talk.wav".into(),
        duration_ms: u64::from(SOUND_MS),
        sha256: servo_studio::ui::sound::sha256_of(&sound).unwrap(),
        offset_ms: 0,
        sensitivity_percent: 50,
    });
    let path = dir.join("show.json");
    servo_studio::project::save(&path, &project).unwrap();
    let data = tempfile::tempdir().unwrap().keep();
    let mut app = StudioApp::new(project, Some(path), no_waker()).with_data_dir(data);
    app.apply(Action::SetLanguage(language));
    let mut harness = common::ui::showing(app, Tab::Motions, (1300.0, 900.0));
    common::ui::run_until(&mut harness, "the sound read", |app| {
        app.desks.sound.view(&app.document.project).read.is_some()
    });
    harness.run_steps(2);
    Some(harness)
}

/// Writes from `slot`: the radio button `from`, then the slot typed into its field.
fn write_from(harness: &mut Harness<'static, StudioApp>, from: &str, slot: u8) {
    // The dialog settles (what the last try said changes its height).
    harness.run_steps(4);
    harness.get_by_role_and_label(Role::RadioButton, from).click();
    harness.run_steps(2);
    let field = || by().role(Role::SpinButton).label(from);
    harness.get(field()).click();
    harness.run();
    harness.get(field()).type_text(&slot.to_string());
    harness.run();
    harness.key_press(egui::Key::Enter);
    harness.run_steps(2);
}

fn motions(harness: &Harness<'static, StudioApp>) -> Vec<Motion> {
    harness.state().document.project.plen2.motions.clone()
}

#[test]
fn on_a_full_robot_a_long_sound_is_followed_by_a_chain_in_the_slots_picked_in_one_undo_step() {
    let dir = tempfile::tempdir().unwrap();
    let Some(mut harness) = full_robot(dir.path(), Language::English) else { return };
    let before = motions(&harness);
    harness.get_by_label("Follow the sound…").click();
    harness.run_steps(3);
    // The free slots (the default): there are none, and it says what to do.
    harness.get_by_label("Make the motion").click();
    harness.run_steps(2);
    assert!(harness.query_by_label_contains("pick the slot to write to").is_some(), "it asks for a slot");
    assert_eq!(motions(&harness), before, "nothing written");
    // From slot 2, replacing what it holds.
    let held = before.iter().find(|m| m.slot == FIRST).unwrap().name.clone();
    write_from(&mut harness, "from slot", FIRST);
    assert!(harness.query_by_label(&format!("replaces {FIRST} {held}")).is_some(), "it says what the slot holds");
    harness.get_by_label("Make the motion").click();
    harness.run_steps(3);
    let after = motions(&harness);
    let chain: Vec<&Motion> = after.iter().filter(|m| m.name == "follow").collect();
    assert!(chain.len() >= 2, "20 s need more than one motion: {}", chain.len());
    for (part, motion) in chain.iter().enumerate() {
        let slot = FIRST + u8::try_from(part).unwrap();
        assert_eq!(motion.slot, slot, "slots 2, 3, …");
        assert!(!motion.frames.is_empty() && motion.frames.len() <= MAX_FRAMES, "{} frames", motion.frames.len());
        assert_eq!(motion.jump_slot, (part + 1 < chain.len()).then_some(slot + 1), "each jumps to the next");
    }
    assert_eq!(after.len(), 90, "the chain replaced as many motions as it took");
    assert!(
        harness.query_by_label_contains(&format!("replaced: {FIRST} {held}")).is_some(),
        "it names what it replaced"
    );
    // The robot plays the chain from its first slot as long as the sound.
    let project = harness.state().document.project.plen2.clone();
    let played = playback::play(&StoredMotions::new(&project), FIRST, [0; playback::DEVICE_IDS], 90 * 20 * 256);
    let played_ms = played.cycles.len() as f64 * playback::Playback::CYCLE_MS;
    assert!(played.ended && (played_ms - f64::from(SOUND_MS)).abs() <= 100.0, "{played_ms} ms played");
    // The frames' strip of the chain's first motion shows it as one.
    harness.get_by_label("Close").click();
    harness.run_steps(2);
    harness.get_by_label(&format!("{FIRST:>2} follow")).click();
    harness.run_steps(3);
    let last = chain.last().unwrap().slot;
    let strip = format!("plays on into slot {} → ", FIRST + 1);
    assert!(
        harness.query_by_label_contains(&strip).is_some()
            && harness.query_by_label_contains(&format!("→ {last} (each jumps")).is_some(),
        "the strip names the chain"
    );
    // One undo step brings every replaced motion back.
    harness.state_mut().apply(Action::Undo);
    harness.run_steps(2);
    assert_eq!(motions(&harness), before, "one undo step");
}

#[test]
fn a_fit_that_cannot_be_made_is_said_in_degrees_in_the_interfaces_language() {
    let dir = tempfile::tempdir().unwrap();
    let Some(mut harness) = full_robot(dir.path(), Language::TraditionalChinese) else { return };
    let before = motions(&harness);
    harness.get_by_label("跟隨聲音…").click();
    harness.run_steps(3);
    harness.get_by_label("產生動作").click();
    harness.run_steps(2);
    assert!(harness.query_by_label_contains("PLEN2 的位置都已使用").is_some(), "every slot taken, in 繁體中文");
    // Slot 89 is the last: one motion, 20 frames, cannot follow 20 s within 1°.
    let held = before.iter().find(|m| m.slot == 89).unwrap().name.clone();
    write_from(&mut harness, "從位置", 89);
    assert!(harness.query_by_label(&format!("取代 89 {held}")).is_some(), "it says what the slot holds");
    harness.get_by_label("產生動作").click();
    harness.run_steps(2);
    let said = harness
        .query_by_label_contains("最多只能放 20 個")
        .expect("the fit's error, in 繁體中文")
        .value()
        .unwrap_or_default();
    assert!(said.contains("在 1.0° 內需要"), "the tolerance asked, in degrees: {said}");
    let smallest: f64 = said
        .rsplit("可行的最小容許誤差為 ")
        .next()
        .and_then(|rest| rest.strip_suffix('°'))
        .and_then(|number| number.parse().ok())
        .unwrap_or_else(|| panic!("the smallest tolerance in degrees: {said}"));
    assert!(smallest > 1.0 && smallest < 90.0, "{said}");
    assert_eq!(motions(&harness), before, "nothing written");
}
