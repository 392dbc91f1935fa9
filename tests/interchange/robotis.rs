//! ROBOTIS motion files. RoboPlus Motion 1.0 (`.mtn`): a step moves every
//! servo to its pose in the step's play time, then pauses; a page plays its
//! steps `repeat` times at `speed rate`, then its next page. R+ Motion 2.0
//! (`.mtnx`): a step's frame is when its pose is reached, in 1/128 s. Checked
//! against those rules worked out by hand, with the PLEN2's own playback
//! (plen2.md §6: 32.768 ms cycles) and the servo board's 10 ms steps.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::float_cmp,
    clippy::cast_precision_loss,
    clippy::cast_possible_truncation
)]

use servo_studio::device::plen2::playback::{self, Playback, StoredMotions};
use servo_studio::interchange::Format;
use servo_studio::project::plen2::Joint;
use servo_studio::project::{Family, Run};
use servo_studio::protocol::plen2::DEVICE_IDS;

use super::built;

/// A step line: id 0's placeholder, ids 1..=18 (a Bioloid humanoid), pause and time in seconds.
fn step(knee: u32, elbow: u32, pause: &str, time: &str) -> String {
    let mut values = [512u32; 19];
    values[0] = 0;
    values[13] = knee; // right knee
    values[5] = elbow; // right elbow
    let values: Vec<String> = values.iter().map(ToString::to_string).collect();
    format!("step={} {pause} {time}\n", values.join(" "))
}

/// Page 1 "Bow": three steps, repeat 2, next page 2, exit page 3; page 2 "Walk"; page 3 "Rest".
pub fn mtn(speed_rate: &str) -> String {
    let enable = format!("enable=0{}\n", " 1".repeat(18));
    format!(
        "type=motion\nversion=1.01\n{enable}motor_type=0\npage_begin\nname=Bow\ncompliance=5 5 5\nplay_param=2 3 2 {speed_rate} 32\n{}{}{}page_end\npage_begin\nname=Walk\nplay_param=0 0 1 1.0 32\n{}{}page_end\npage_begin\nname=Rest\nplay_param=0 0 1 1.0 32\n{}page_end\npage_begin\nname=\nplay_param=0 0 1 1.0 32\npage_end\n",
        step(612, 512, "0.000", "0.496"),
        step(712, 400, "0.296", "1.000"),
        step(512, 512, "0.100", "0.250"),
        step(562, 512, "0.000", "0.300"),
        step(512, 512, "0.000", "0.300"),
        step(512, 512, "0.500", "0.504"),
    )
}

/// AX units as tenths of a degree (300° over 1024 units).
fn tenths(units: u32) -> i16 {
    ((f64::from(units) - 512.0) * 300.0 / 1024.0 * 10.0).round() as i16
}

/// The times (ms from the start) at which the source says each pose is reached and each pause ends.
fn boundaries(steps: &[(f64, f64)], speed: f64) -> Vec<f64> {
    let mut at = 0.0;
    let mut out = Vec::new();
    for (time, pause) in steps {
        at += time * 1000.0 / speed;
        out.push(at);
        if *pause > 0.0 {
            at += pause * 1000.0 / speed;
            out.push(at);
        }
    }
    out
}

/// When each frame of `slot` is reached in its first pass: the last cycle of
/// the first run approaching it, cycle k at k × 32.768 ms (as `trajectory`
/// writes it: cycle 0 as `$PM` starts).
fn reached(play: &Playback, slot: u8, frames: usize) -> Vec<f64> {
    let mut ends = Vec::new();
    for (cycle, approached) in play.frames.iter().enumerate() {
        let next = play.frames.get(cycle + 1);
        if approached.0 == slot && next != Some(approached) {
            ends.push(cycle as f64 * Playback::CYCLE_MS);
        }
        if ends.len() == frames {
            break;
        }
    }
    ends
}

fn knee(values: &[i16; DEVICE_IDS]) -> i16 {
    values[usize::from(Joint::RightKneePitch.device_id())]
}

#[test]
fn an_mtn_page_plays_on_a_plen2_within_one_cycle_of_roboplus_timing() {
    for (speed_text, speed) in [("1.0", 1.0), ("2.0", 2.0)] {
        let (_, _, built) = built(Format::Mtn, &mtn(speed_text), Family::Plen2);
        let plen2 = &built.project.plen2;
        let bow = plen2.motions.iter().find(|m| m.name == "Bow").unwrap();
        let stored = StoredMotions::new(plen2);
        let play = playback::play(&stored, bow.slot, [0; DEVICE_IDS], 2000);
        let expected = boundaries(&[(0.496, 0.0), (1.0, 0.296), (0.25, 0.1)], speed);
        assert_eq!(bow.frames.len(), expected.len(), "a frame per move and per pause");
        let got = reached(&play, bow.slot, bow.frames.len());
        for (got, want) in got.iter().zip(&expected) {
            assert!(
                (got - want).abs() <= Playback::CYCLE_MS,
                "speed {speed}: reached at {got} ms, RoboPlus at {want} ms"
            );
        }
        // Poses within the unit conversion: the knee's AX units as tenths.
        let knees: Vec<i16> = bow.frames.iter().map(|f| f.values_tenths_deg.get(Joint::RightKneePitch)).collect();
        assert_eq!(knees, [tenths(612), tenths(712), tenths(712), tenths(512), tenths(512)]);
        let first = play.frames.iter().rposition(|a| *a == (bow.slot, 0)).unwrap();
        // What the firmware holds at the end of the move: the frame's value, or a
        // tenth below it (16.16 steps floor: plen2.md §6).
        let held = knee(&play.cycles[first]);
        assert!((tenths(612) - 1..=tenths(612)).contains(&held), "{held}");
        // Repeat 2: one loop of every frame; next page: a jump to Walk's slot.
        let walk = plen2.motions.iter().find(|m| m.name == "Walk").unwrap();
        assert_eq!(bow.loop_range.map(|l| (l.begin_frame, l.end_frame, l.count)), Some((0, 4, 1)));
        assert_eq!(bow.jump_slot, Some(walk.slot));
        // Exit page: a play list of the page, then its exit page.
        let rest = plen2.motions.iter().find(|m| m.name == "Rest").unwrap();
        let list = plen2.play_lists.iter().find(|l| l.name == "Bow then exit").unwrap();
        assert_eq!(list.entries.iter().map(|e| e.slot).collect::<Vec<_>>(), [bow.slot, rest.slot]);
        assert_eq!(plen2.motions.len(), 3, "the empty page is no motion");
    }
}

#[test]
fn an_mtn_page_on_a_servo_board_is_actions_of_its_play_time_and_delays_of_its_pauses() {
    let (_, _, built) = built(Format::Mtn, &mtn("1.0"), Family::Servo);
    let servo = &built.project.servo;
    let body = servo.macros.iter().find(|m| m.caption == "Bow steps").unwrap();
    let intervals: Vec<Vec<(u8, i16, i16)>> = body
        .commands
        .iter()
        .filter_map(|c| match c.run {
            Run::Action { action_id } => Some(
                servo
                    .action(action_id)
                    .unwrap()
                    .steps
                    .iter()
                    .filter(|s| s.servo_id == 13)
                    .map(|s| (s.servo_id, s.degree, s.interval_10ms))
                    .collect(),
            ),
            _ => None,
        })
        .collect();
    // 612 AX units is +29.3°: the board's whole degree is 29; 0.496 s is 50 updates (rounded).
    assert_eq!(intervals, [vec![(13, 29, 50)], vec![(13, 59, 100)], vec![(13, 0, 25)]]);
    let delays: Vec<i32> = body
        .commands
        .iter()
        .filter_map(|c| if let Run::Delay { delay_ms } = c.run { Some(delay_ms) } else { None })
        .collect();
    // The pause ends at 0.496 + 1.000 + 0.296 s, as RoboPlus plays it: the
    // 4 ms the first move's whole updates ran over come off it.
    assert_eq!(delays, [292, 100]);
    let play = servo.macros.iter().find(|m| m.caption == "Bow").unwrap();
    assert_eq!(play.commands[0].run, Run::Macro { macro_id: body.id });
    assert_eq!(play.commands[0].loop_count, 2, "repeat 2");
    let walk = servo.macros.iter().find(|m| m.caption == "Walk").unwrap();
    assert_eq!(play.commands[1].run, Run::Macro { macro_id: walk.id }, "then the next page");
    assert!(servo.macros.iter().any(|m| m.caption == "Bow then exit"));
    assert!(built.report.approximated.iter().any(|n| n.contains("10 ms")), "{:?}", built.report);
}

#[test]
fn a_page_asked_for_comes_with_the_pages_it_leads_to() {
    let source = servo_studio::interchange::read(Format::Mtn, &mtn("1.0")).unwrap();
    let map = servo_studio::interchange::JointMap::for_source(&source, Family::Plen2, None);
    let mut options = servo_studio::interchange::build::Options::new(Family::Plen2);
    options.selection = servo_studio::interchange::build::Selection::Page(2);
    let built = servo_studio::interchange::build::build(&source, &map, &options).unwrap();
    assert_eq!(built.project.plen2.motions.iter().map(|m| m.name.as_str()).collect::<Vec<_>>(), ["Walk"]);
    options.selection = servo_studio::interchange::build::Selection::Page(9);
    let missing = servo_studio::interchange::build::build(&source, &map, &options).unwrap_err().to_string();
    assert!(missing.contains("page 9 is not in the file") && missing.contains("page 1 \"Bow\""), "{missing}");
}

pub const MTNX: &str = r#"<?xml version="1.0" encoding="utf-8"?>
<Root>
  <FlowRoot>
    <Flow name="show" return="-1">
      <units>
        <unit main="Wave" mainSpeed="1" loop="3" exit="Rest" exitSpeed="1" callSite="False" />
      </units>
    </Flow>
  </FlowRoot>
  <PageRoot>
    <Page name="Wave">
      <param compileSize="1" acceleration="32" softness="5 5 5 5 5 5 5 5 5 5 5 5 5 5 5 5 5 5" />
      <steps>
        <step frame="64" pose="0 0 0 0 -30 0 0 0 0 0 0 0 0 0 0 0 0 0" />
        <step frame="192" pose="0 0 0 0 30.5 0 0 0 0 0 0 0 12.3 0 0 0 0 0" />
        <step frame="256" pose="0 0 0 0 30.5 0 0 0 0 0 0 0 12.3 0 0 0 0 0" />
      </steps>
    </Page>
    <Page name="Rest">
      <steps>
        <step frame="128" pose="0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0" />
      </steps>
    </Page>
  </PageRoot>
</Root>"#;

#[test]
fn an_mtnx_page_is_timed_in_128ths_and_its_flow_is_a_play_list() {
    let (_, _, built) = built(Format::Mtnx, MTNX, Family::Plen2);
    let plen2 = &built.project.plen2;
    let wave = plen2.motions.iter().find(|m| m.name == "Wave").unwrap();
    let stored = StoredMotions::new(plen2);
    let play = playback::play(&stored, wave.slot, [0; DEVICE_IDS], 2000);
    // Reached at 64/128 s, 192/128 s and 256/128 s: 500, 1500 and 2000 ms.
    let got = reached(&play, wave.slot, wave.frames.len());
    for (got, want) in got.iter().zip([500.0, 1500.0, 2000.0]) {
        assert!((got - want).abs() <= Playback::CYCLE_MS, "reached at {got} ms, R+ Motion at {want} ms");
    }
    // Pose 5 is id 5, the right elbow of a Bioloid humanoid: degrees already.
    assert_eq!(wave.frames[1].values_tenths_deg.get(Joint::RightElbowRoll), 305);
    assert_eq!(wave.frames[1].values_tenths_deg.get(Joint::RightKneePitch), 123);
    let list = plen2.play_lists.iter().find(|l| l.name == "show").unwrap();
    let rest = plen2.motions.iter().find(|m| m.name == "Rest").unwrap();
    assert_eq!(list.entries.iter().map(|e| (e.slot, e.plays)).collect::<Vec<_>>(), [(wave.slot, 3), (rest.slot, 1)]);
}

#[test]
fn malformed_motion_files_say_which_line() {
    let read = |format, text: &str| servo_studio::interchange::read(format, text).unwrap_err().to_string();
    let text = mtn("1.0");
    let word = read(Format::Mtn, &text.replacen("0.496", "half", 1));
    assert!(word.starts_with("line 9: <step>: value \"half\" is not a number"), "{word}");
    let cut = read(Format::Mtn, &text[..text.find("page_end").unwrap()]);
    assert!(cut.contains("never ends") && cut.contains("cut short"), "{cut}");
    assert!(read(Format::Mtn, "hello\n").starts_with("line 1:"));
    let frame = read(Format::Mtnx, &MTNX.replace(r#"frame="192""#, r#"frame="late""#));
    assert!(frame.starts_with("line 15: <step>: frame \"late\" is not a number"), "{frame}");
    let order = read(Format::Mtnx, &MTNX.replace(r#"frame="256""#, r#"frame="100""#));
    assert!(order.contains("comes before the step above it"), "{order}");
    let cut = read(Format::Mtnx, &MTNX[..MTNX.find("</PageRoot>").unwrap()]);
    assert!(cut.contains("never closed"), "{cut}");
    assert!(read(Format::Mtnx, "<Root/>").contains("no <Page>"));
    let unit = read(Format::Mtnx, &MTNX.replace(r#"main="Wave""#, r#"main="Jump""#));
    assert!(unit.contains("line 6: <unit>: page \"Jump\" is not in the file"), "{unit}");
}
