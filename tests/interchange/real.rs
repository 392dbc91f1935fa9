//! Files as the real tools write them (`tests/fixtures/interchange`: the
//! Blender add-on's own example exports from four of its releases, and
//! RoboPlus and R+ Motion files written the way those tools save them; the
//! folder's README says where each variant was seen). Each converts for both
//! boards and passes `check`; key times and values are worked out here from
//! each format's own rules, not from the converter. A folder of further real
//! files named by `SERVO_STUDIO_REAL_FILES` is run through the same checks.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::float_cmp, clippy::cast_precision_loss)]

use std::path::{Path, PathBuf};

use serde_json::Value;
use servo_studio::device::plen2::playback::{self, Playback, StoredMotions};
use servo_studio::interchange::build::{self, BuildError, Options};
use servo_studio::interchange::{Body, Format, JointMap, Source, Target, text};
use servo_studio::project::plen2::Joint;
use servo_studio::project::{Family, Run, ServoProject};
use servo_studio::protocol::plen2::DEVICE_IDS;

/// Half a servo board update, ms.
const HALF_UPDATE_MS: f64 = 5.0;

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/interchange")
}

fn fixture(name: &str) -> PathBuf {
    fixtures().join(name)
}

/// Every tool file in `dir` and its folders (not recipes, notes or files cut short on purpose).
fn tool_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if path.is_dir() {
            tool_files(&path, out);
        } else if !name.ends_with(".py") && !name.ends_with(".md") && !name.starts_with("cut-short") {
            out.push(path);
        }
    }
}

fn read(path: &Path) -> Source {
    let bytes = std::fs::read(path).unwrap();
    let decoded = text::decode(bytes.as_slice()).unwrap();
    servo_studio::interchange::read_decoded(None, &decoded)
        .unwrap_or_else(|error| panic!("{}: {error}", path.display()))
        .unwrap_or_else(|| panic!("{}: no format told from its content", path.display()))
}

#[test]
fn every_real_file_converts_for_both_boards_and_passes_check() {
    let mut files = Vec::new();
    tool_files(&fixtures(), &mut files);
    let hidden = std::env::var_os("SERVO_STUDIO_REAL_FILES").map(PathBuf::from);
    if let Some(dir) = &hidden {
        let before = files.len();
        tool_files(dir, &mut files);
        eprintln!("SERVO_STUDIO_REAL_FILES: {} more files from {}", files.len() - before, dir.display());
    }
    assert!(files.len() >= 12, "{files:?}");
    let mut plen2_made = 0;
    for path in &files {
        let source = read(path);
        for family in [Family::Servo, Family::Plen2] {
            let map = JointMap::for_source(&source, family, None);
            let drives = map.entries.iter().any(|entry| entry.target.is_some_and(|t| t.family() == family));
            match build::build(&source, &map, &Options::new(family)) {
                Ok(built) => {
                    let problems = servo_studio::project::validate(&built.project);
                    assert!(
                        !servo_studio::project::has_errors(&problems),
                        "{} → {}: {problems:?}",
                        path.display(),
                        family.name()
                    );
                    plen2_made += usize::from(family == Family::Plen2);
                }
                // A robot that is no humanoid, or more motions than 90 slots: said, not guessed.
                Err(BuildError::Unmapped { .. }) if !drives => {}
                Err(BuildError::TooBig(said)) if family == Family::Plen2 => assert!(said.contains("slots"), "{said}"),
                Err(error) => panic!("{} → {}: {error}", path.display(), family.name()),
            }
        }
    }
    assert!(plen2_made >= 5, "the RoboPlus and Bioloid files become PLEN2 motions: {plen2_made}");
}

/// A RoboPlus page as the format says it plays: each step moves in its play
/// time, then pauses; both divided by the page's speed rate.
#[derive(Debug)]
struct Page {
    name: String,
    next: u32,
    repeat: u32,
    speed: f64,
    /// The inertial force: each step's ease, in ticks.
    ease: u32,
    /// `(play time, pause)` in seconds.
    steps: Vec<(f64, f64)>,
}

/// The pages of a RoboPlus text, read here by the format's own rules.
fn pages(text: &str) -> Vec<Page> {
    let number = |word: &str| word.replace(',', ".").parse::<f64>().unwrap();
    let mut pages: Vec<Page> = Vec::new();
    for line in text.lines() {
        let (key, value) = line.split_once('=').unwrap_or((line, ""));
        match key {
            "page_begin" => {
                pages.push(Page { name: String::new(), next: 0, repeat: 1, speed: 1.0, ease: 0, steps: Vec::new() });
            }
            "name" => pages.last_mut().unwrap().name = value.to_string(),
            "play_param" => {
                let words: Vec<&str> = value.split_whitespace().collect();
                let page = pages.last_mut().unwrap();
                (page.next, page.repeat, page.speed, page.ease) =
                    (words[0].parse().unwrap(), words[2].parse().unwrap(), number(words[3]), words[4].parse().unwrap());
            }
            "step" => {
                let words: Vec<&str> = value.split_whitespace().collect();
                let time = number(words[words.len() - 1]);
                let pause = number(words[words.len() - 2]);
                pages.last_mut().unwrap().steps.push((time, pause));
            }
            _ => {}
        }
    }
    pages
}

/// When RoboPlus's controller reaches each pose of `page` (`false`) and ends
/// each stand (`true`), ms from `from_ms`, and when the page ends: its
/// controller's own times (`super::robotis::controller`), divided by the
/// page's speed rate (docs/import-export.md).
fn boundaries(page: &Page, from_ms: f64) -> (Vec<(f64, bool)>, f64) {
    let (times, end) = super::robotis::controller(&page.steps, page.ease, 0.0);
    let at = |ms: f64| from_ms + ms / page.speed;
    (times.into_iter().map(|(ms, stand)| (at(ms), stand)).collect(), at(end))
}

fn walk_text() -> String {
    std::fs::read_to_string(fixture("roboplus/walk.mtn.txt")).unwrap()
}

#[test]
fn roboplus_files_as_saved_by_roboplus_on_any_locale_or_edited_read_alike() {
    let plain = read(&fixture("roboplus/walk.mtn.txt"));
    for (name, note) in [
        ("roboplus/walk-as-saved.mtn", "checksum after the last page matches"),
        ("roboplus/walk-decimal-comma.mtn", "decimal-comma locale"),
        ("roboplus/walk-edited-by-hand.mtn", "edited outside RoboPlus"),
    ] {
        let source = read(&fixture(name));
        assert_eq!(source.format, Format::Mtn, "{name}");
        assert_eq!(source.channels, plain.channels, "{name}");
        let names = |s: &Source| s.clips.iter().map(|c| c.name.to_lowercase()).collect::<Vec<_>>();
        assert_eq!(names(&source), names(&plain), "{name}: the edit renamed Init to INIT, nothing else");
        for (clip, want) in source.clips.iter().zip(&plain.clips) {
            assert_eq!(
                (&clip.body, clip.speed, clip.repeat, clip.next),
                (&want.body, want.speed, want.repeat, want.next)
            );
        }
        assert!(source.notes.iter().any(|n| n.contains(note)), "{name}: {:?}", source.notes);
    }
}

/// Where a servo-board macro's commands leave the board's clock: after each
/// action (its longest step) and each delay.
fn board_times(servo: &ServoProject, commands: &[servo_studio::project::Command]) -> Vec<(f64, bool)> {
    let mut at = 0.0;
    commands
        .iter()
        .map(|command| match command.run {
            Run::Action { action_id } => {
                let action = servo.action(action_id).unwrap();
                at += action.steps.iter().map(|s| f64::from(s.interval_10ms) * 10.0).fold(0.0, f64::max);
                (at, false)
            }
            Run::Delay { delay_ms } => {
                at += f64::from(delay_ms);
                (at, true)
            }
            Run::Macro { .. } => panic!("a page's steps are actions and delays"),
        })
        .collect()
}

#[test]
fn roboplus_times_on_a_servo_board_are_kept_at_every_key_not_rounded_step_by_step() {
    let source = read(&fixture("roboplus/walk-as-saved.mtn"));
    let map = JointMap::for_source(&source, Family::Servo, None);
    let built = build::build(&source, &map, &Options::new(Family::Servo)).unwrap();
    let servo = &built.project.servo;
    let mut checked = 0;
    for page in pages(&walk_text()).iter().filter(|p| !p.steps.is_empty()) {
        let body = servo
            .macros
            .iter()
            .find(|m| m.caption == format!("{} steps", page.name))
            .or_else(|| servo.macros.iter().find(|m| m.caption == page.name))
            .unwrap();
        let board = board_times(servo, &body.commands);
        let mut board = board.iter().peekable();
        for (want, is_pause) in boundaries(page, 0.0).0 {
            // A pause the board's clock already covers needs no delay of its own.
            let got = if is_pause {
                board.next_if(|(_, pause)| *pause).map(|(t, _)| *t)
            } else {
                board.next().map(|(t, _)| *t)
            };
            let got = got.unwrap_or(want);
            assert!((got - want).abs() <= HALF_UPDATE_MS, "{}: key at {want:.1} ms plays at {got} ms", page.name);
            checked += 1;
        }
        assert!(board.next().is_none(), "{}: one action per step, one delay per pause", page.name);
    }
    assert!(checked >= 12);
    let said: Vec<&String> =
        built.report.approximated.iter().filter(|n| n.contains("rounding never adding up")).collect();
    assert_eq!(said.len(), 1, "said once, the farthest of every page: {:?}", built.report);
}

/// When each frame of a playback is left: cycle k is output at k × 32.768 ms (cycle 0 as `$PM` starts).
fn frame_ends(play: &Playback) -> Vec<f64> {
    let mut ends = Vec::new();
    for (cycle, approached) in play.frames.iter().enumerate() {
        if play.frames.get(cycle + 1).is_some_and(|next| next != approached) {
            ends.push(cycle as f64 * Playback::CYCLE_MS);
        }
    }
    ends.push((play.frames.len() - 1) as f64 * Playback::CYCLE_MS);
    ends
}

#[test]
fn a_roboplus_page_chain_plays_on_a_plen2_as_one_across_the_jump() {
    let source = read(&fixture("roboplus/walk-as-saved.mtn"));
    let map = JointMap::for_source(&source, Family::Plen2, None);
    let built = build::build(&source, &map, &Options::new(Family::Plen2)).unwrap();
    let plen2 = &built.project.plen2;
    let all = pages(&walk_text());
    let (start, next) = (&all[1], &all[2]);
    assert_eq!((start.name.as_str(), start.next, next.name.as_str()), ("F_S", 3, "F_M"));
    let first = plen2.motions.iter().find(|m| m.name == "F_S").unwrap();
    let second = plen2.motions.iter().find(|m| m.name == "F_M").unwrap();
    assert_eq!(first.jump_slot, Some(second.slot));
    let stored = StoredMotions::new(plen2);
    let play = playback::play(&stored, first.slot, [0; DEVICE_IDS], 400);
    // The chain as RoboPlus plays it: the next page starts as the last one ends.
    let (mut want, joined) = boundaries(start, 0.0);
    want.extend(boundaries(next, joined).0);
    // A stand within one cycle is no frame of its own (its time is kept by the frames after it).
    let half = Playback::CYCLE_MS / 2.0;
    let mut stood = 0.0;
    let want: Vec<f64> = want
        .iter()
        .filter(|(ms, stand)| {
            // A stand is a frame when it ends on a later cycle than it starts.
            let kept = !stand || (ms / Playback::CYCLE_MS).round() > (stood / Playback::CYCLE_MS).round();
            stood = *ms;
            kept
        })
        .map(|(ms, _)| *ms)
        .collect();
    let got = frame_ends(&play);
    assert_eq!(got.len(), want.len(), "a frame per move: {got:?} for {want:?}");
    for (got, want) in got.iter().zip(&want) {
        assert!((got - want).abs() <= half + 1e-9, "reached at {got:.1} ms, RoboPlus at {want:.1} ms");
    }
    let whole = want.last().unwrap();
    assert!((got.last().unwrap() - whole).abs() <= half, "the chain ends within half a cycle of {whole:.1} ms");
}

#[test]
fn an_r_plus_file_is_read_for_the_robot_it_declares() {
    let source = read(&fixture("rplus/robot-xl320.mtnx"));
    let keys: Vec<&str> = source.channels.iter().map(|c| c.key.as_str()).collect();
    assert_eq!(keys, ["1", "2", "5"], "the declared ids, joint 3 switched off");
    assert!(source.channels.iter().all(|c| c.limits == Some((-150.0, 150.0))), "an XL-320 turns ±150°");
    assert!(source.dropped.iter().any(|d| d.contains("switched off")));
    assert!(source.dropped.iter().any(|d| d.contains("\"==== START ====\": no units")), "{:?}", source.dropped);
    assert!(source.notes.iter().any(|n| n.contains("a robot of 4 × XL-320")), "{:?}", source.notes);
    assert!(source.notes.iter().any(|n| n.contains("no PLEN2 joint is guessed")), "{:?}", source.notes);
    let flow = source.clips.iter().find(|c| c.name == "Greet").unwrap();
    let Body::Chain(links) = &flow.body else { panic!() };
    let named: Vec<(&str, u32, f64)> =
        links.iter().map(|l| (source.clips[l.clip].name.as_str(), l.plays, l.speed)).collect();
    assert_eq!(named, [("Bow", 1, 1.0), ("Wave", 2, 1.5), ("Rest", 1, 1.0)]);
    // The PLEN2 guess is not made for a robot that is not a humanoid of Bioloid ids.
    let map = JointMap::for_source(&source, Family::Plen2, None);
    assert!(map.entries.iter().all(|e| e.target.is_none()));
    let said = build::build(&source, &map, &Options::new(Family::Plen2)).unwrap_err().to_string();
    assert!(said.contains("joint map"), "{said}");
    // On a servo board: Bow's steps end at 51, 114 and 191 / 128 s.
    let map = JointMap::for_source(&source, Family::Servo, None);
    let built = build::build(&source, &map, &Options::new(Family::Servo)).unwrap();
    let servo = &built.project.servo;
    let bow = servo.macros.iter().find(|m| m.caption == "Bow").unwrap();
    let got: Vec<f64> = board_times(servo, &bow.commands).iter().map(|(t, _)| *t).collect();
    let want = [51.0, 114.0, 191.0].map(|frame| frame * 1000.0 / 128.0);
    assert_eq!(got.len(), 3);
    for (got, want) in got.iter().zip(want) {
        assert!((got - want).abs() <= HALF_UPDATE_MS, "Bow: a key at {want:.2} ms plays at {got} ms");
    }
    let ids: Vec<u8> = servo.servos.iter().map(|s| s.id).collect();
    assert_eq!(ids, [1, 2, 5]);
    assert!(servo.servos.iter().all(|s| (s.min_deg, s.max_deg) == (-150, 150)));
}

#[test]
fn a_bioloid_declared_in_r_plus_drives_a_plen2_by_its_ids() {
    let source = read(&fixture("rplus/bioloid-ax12.mtnx"));
    let map = JointMap::for_source(&source, Family::Plen2, None);
    let joint = |key: &str| map.entry(key).and_then(|e| e.target);
    assert_eq!(joint("1"), Some(Target::Joint(Joint::RightShoulderPitch)));
    assert_eq!(joint("14"), Some(Target::Joint(Joint::LeftKneePitch)));
    let built = build::build(&source, &map, &Options::new(Family::Plen2)).unwrap();
    let plen2 = &built.project.plen2;
    let raise = plen2.motions.iter().find(|m| m.name == "Raise").unwrap();
    let values: Vec<(i16, i16)> = raise
        .frames
        .iter()
        .map(|f| (f.values_tenths_deg.get(Joint::RightShoulderPitch), f.values_tenths_deg.get(Joint::RightKneePitch)))
        .collect();
    assert_eq!(values, [(-450, 0), (-900, 105)], "R+ poses are degrees from centre");
    let stored = StoredMotions::new(plen2);
    let play = playback::play(&stored, raise.slot, [0; DEVICE_IDS], 200);
    let got = frame_ends(&play);
    for (got, want) in got.iter().zip([64.0, 160.0].map(|f| f * 1000.0 / 128.0)) {
        assert!((got - want).abs() <= Playback::CYCLE_MS / 2.0, "reached at {got:.1} ms, R+ at {want:.1} ms");
    }
    let hello = plen2.play_lists.iter().find(|l| l.name == "Hello").unwrap();
    assert_eq!(hello.entries.len(), 2, "the flow's two units");
    assert!(plen2.play_lists.iter().all(|l| !l.entries.is_empty()), "an empty flow is no play list");
}

/// The add-on's positions per frame for each servo, read here from the JSON
/// by the layout each release wrote.
fn addon_rows(value: &Value) -> (f64, Vec<(String, Vec<f64>)>) {
    let number = |v: &Value| v.as_f64().or_else(|| v.as_str().and_then(|s| s.parse().ok())).unwrap();
    let fps = value["fps"].as_f64().unwrap();
    let mut servos: Vec<(String, Vec<f64>)> = Vec::new();
    if let Some(Value::Array(frames)) = value.get("positions") {
        // One object per frame; a servo left out holds its last position.
        for frame in frames {
            for (id, position) in frame.as_object().unwrap() {
                if !servos.iter().any(|(key, _)| key == id) {
                    servos.push((id.clone(), Vec::new()));
                }
                let _ = position;
            }
        }
        for (id, column) in &mut servos {
            let mut last = None;
            for frame in frames {
                last = frame.get(id.as_str()).map(number).or(last);
                column.push(last.unwrap());
            }
        }
    } else if let Some(Value::Object(by_id)) = value.get("servos") {
        for (id, servo) in by_id {
            servos.push((id.clone(), servo["positions"].as_array().unwrap().iter().map(number).collect()));
        }
    } else {
        let bones = value.get("positions").or_else(|| value.get("pulses")).unwrap().as_object().unwrap();
        for (bone, list) in bones {
            servos.push((bone.clone(), list.as_array().unwrap().iter().map(number).collect()));
        }
    }
    (fps, servos)
}

#[test]
fn every_blender_add_on_layout_is_read_with_its_values_and_never_taken_for_a_motion_json() {
    let dir = fixture("blender");
    let mut files = Vec::new();
    tool_files(&dir, &mut files);
    assert_eq!(files.len(), 4);
    for path in &files {
        let text = std::fs::read_to_string(path).unwrap();
        assert_eq!(Format::guess(&text), Some(Format::Blender), "{}", path.display());
        assert!(!servo_studio::project::motion_json::looks_like_motion(&text), "{}", path.display());
        let (fps, servos) = addon_rows(&serde_json::from_str(&text).unwrap());
        let source = read(path);
        let Body::Samples { fps: read_fps, rows } = &source.clips[0].body else { panic!() };
        assert_eq!(*read_fps, fps);
        for (column, (id, want)) in servos.iter().enumerate() {
            let channel = source.channels.iter().position(|c| &c.key == id).unwrap();
            let got: Vec<f64> = rows.iter().map(|row| row[channel]).collect();
            assert_eq!(&got, want, "{} servo {id} (column {column})", path.display());
        }
    }
}

#[test]
fn files_cut_short_name_their_line_and_say_what_to_try() {
    let bytes = std::fs::read(fixture("rplus/cut-short.mtnx")).unwrap();
    let decoded = text::decode(bytes.as_slice()).unwrap();
    let lines = decoded.text.lines().count();
    let error = servo_studio::interchange::read_decoded(None, &decoded).unwrap_err();
    assert_eq!(error.line, Some(lines), "{error}");
    assert!(error.message.contains("cut short"), "{error}");
    let json = std::fs::read_to_string(fixture("blender/addon-2023-servos-ik.json")).unwrap();
    let cut = &json[..json.len() / 2];
    let error = servo_studio::interchange::read_decoded(None, &text::decode(cut.as_bytes()).unwrap()).unwrap_err();
    assert_eq!(error.line, Some(cut.lines().count()), "{error}");
    assert!(error.message.contains("cut short"), "{error}");
}

/// Each add-on export goes into a servo project and back out as add-on JSON
/// at its own frame rate: every frame of every servo reads back within the
/// fit's tolerance (1°) of the file, in the file's own unit.
#[test]
fn every_blender_export_goes_to_a_board_and_back_within_the_tolerance() {
    let mut files = Vec::new();
    tool_files(&fixture("blender"), &mut files);
    for path in &files {
        let source = read(path);
        let map = JointMap::for_source(&source, Family::Servo, None);
        let built = build::build(&source, &map, &Options::new(Family::Servo)).unwrap();
        let servo = &built.project.servo;
        let Body::Samples { fps, rows } = &source.clips[0].body else { panic!() };
        let (out, _) =
            servo_studio::interchange::export::blender_servo(servo, servo.macros[0].id, *fps, Some(&map)).unwrap();
        let again = servo_studio::interchange::read(Format::Blender, &out).unwrap();
        let Body::Samples { rows: back, .. } = &again.clips[0].body else { panic!() };
        assert!(back.len() + 1 >= rows.len(), "{}: {} frames back of {}", path.display(), back.len(), rows.len());
        for (channel, original) in source.channels.iter().enumerate() {
            let entry = map.entry(&original.key).unwrap();
            // Written under the file's own key, in its own unit (the map given to the export says them).
            let column = again.channels.iter().position(|c| c.key == original.key).unwrap();
            let back_map = JointMap::for_source(&again, Family::Servo, None);
            let back_entry = back_map.entry(&again.channels[column].key).unwrap();
            for (frame, (want, got)) in rows.iter().zip(back).enumerate() {
                let (want, got) = (entry.degrees(want[channel]), back_entry.degrees(got[column]));
                assert!(
                    (want - got).abs() <= 1.0 + 0.05,
                    "{} servo {} frame {frame}: {want:.2}° back as {got:.2}°",
                    path.display(),
                    original.key
                );
            }
        }
    }
}

/// A RoboPlus file straight onto DYNAMIXEL IDs: each enabled column the AX-12A
/// of that ID, its values kept as written (AX units), and each page a motion
/// whose steps end when RoboPlus's controller reaches each pose and ends each
/// pause, at the page's speed rate — worked out here from the format's own
/// rules, to the rounding of a whole millisecond.
#[test]
fn a_roboplus_file_goes_onto_dynamixel_ids_in_ax_units_timed_as_the_controller_plays_it() {
    use servo_studio::project::dynamixel::DynamixelSection;
    let source = read(&fixture("roboplus/walk-as-saved.mtn"));
    let (project, report) = servo_studio::interchange::dynamixel::build(&source, &build::Selection::All).unwrap();
    assert_eq!(project.family, Family::Dynamixel);
    assert!(servo_studio::project::validate(&project).is_empty(), "{:?}", servo_studio::project::validate(&project));
    let section = DynamixelSection::of(&project);
    let ids: Vec<(u8, u16)> = section.servos.iter().map(|servo| (servo.id, servo.model_number)).collect();
    assert_eq!(ids, (1..=18).map(|id| (id, 12)).collect::<Vec<_>>(), "ids 1–18 enabled, AX-12A units");
    let text = walk_text();
    // Every step line's values, page by page, as written.
    let mut written: Vec<Vec<Vec<u32>>> = Vec::new();
    for line in text.lines() {
        if line == "page_begin" {
            written.push(Vec::new());
        } else if let Some(values) = line.strip_prefix("step=") {
            let values: Vec<u32> = values.split_whitespace().take(26).map(|word| word.parse().unwrap()).collect();
            written.last_mut().unwrap().push(values);
        }
    }
    let mut checked = 0;
    for ((page, values), motion) in
        pages(&text).iter().zip(&written).filter(|(page, _)| !page.steps.is_empty()).zip(&section.motions)
    {
        assert!(motion.name.ends_with(&page.name), "{} for {}", motion.name, page.name);
        let (times, _) = boundaries(page, 0.0);
        let mut end_ms = 0u64;
        let ends: Vec<u64> = motion
            .steps
            .iter()
            .map(|step| {
                end_ms += u64::from(step.duration_ms);
                end_ms
            })
            .collect();
        if page.repeat == 1 {
            assert_eq!(times.len(), ends.len(), "{}: a step for each move and each pause", page.name);
        }
        for ((want, _), got) in times.iter().zip(&ends) {
            assert!((*got as f64 - want).abs() <= 1.0, "{}: a key at {want:.2} ms ends at {got} ms", page.name);
            checked += 1;
        }
        // Each pose as written: the move to it and its pause hold the file's values.
        let poses: Vec<&std::collections::BTreeMap<u8, u32>> =
            motion.steps.iter().map(|step| &step.positions).collect();
        let mut poses = poses.into_iter();
        for row in values {
            let pose = poses.next().unwrap();
            for id in 1..=18u8 {
                assert_eq!(pose[&id], row[usize::from(id)], "{}: servo {id}", page.name);
            }
            if poses.clone().next().is_some_and(|next| next == pose) {
                poses.next();
            }
        }
    }
    assert!(checked >= 12, "{checked}");
    assert!(report.converted.len() == section.motions.len());
}

/// R+ poses in degrees go onto the servos the file's robot declares, in their
/// own units: an XL-320's and an AX-12A's 1024 over 300°, a pose at 150° its last position.
#[test]
fn r_plus_poses_go_onto_the_declared_servos_in_their_own_units() {
    use servo_studio::project::dynamixel::DynamixelSection;
    for (file, model) in [("rplus/robot-xl320.mtnx", 350), ("rplus/bioloid-ax12.mtnx", 12)] {
        let source = read(&fixture(file));
        let (project, _) = servo_studio::interchange::dynamixel::build(&source, &build::Selection::All).unwrap();
        assert!(servo_studio::project::validate(&project).is_empty(), "{file}");
        let section = DynamixelSection::of(&project);
        assert!(section.servos.iter().all(|servo| servo.model_number == model), "{file}: {:?}", section.servos);
        for motion in &section.motions {
            for step in &motion.steps {
                assert!(step.positions.values().all(|position| *position <= 1023), "{file}: {step:?}");
            }
        }
    }
    // Bow's poses reached at 51, 114 and 191 / 128 s, as on a servo board.
    let source = read(&fixture("rplus/robot-xl320.mtnx"));
    let (project, _) =
        servo_studio::interchange::dynamixel::build(&source, &build::Selection::Named("Bow".into())).unwrap();
    let section = DynamixelSection::of(&project);
    let mut end = 0u32;
    let ends: Vec<u32> = section.motions[0]
        .steps
        .iter()
        .map(|step| {
            end += step.duration_ms;
            end
        })
        .collect();
    let want = [51.0, 114.0, 191.0].map(|frame: f64| frame * 1000.0 / 128.0);
    assert_eq!(ends.len(), 3);
    for (got, want) in ends.iter().zip(want) {
        assert!((f64::from(*got) - want).abs() <= 0.5, "Bow: a pose at {want:.2} ms reached at {got} ms");
    }
}
