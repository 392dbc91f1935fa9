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

/// One section of a step as ROBOTIS's Action engine plays it.
#[derive(Clone, Copy, PartialEq)]
enum Section {
    EaseIn,
    Straight,
    EaseOut,
    Pause,
}

/// A RoboPlus page's steps (`(play time, pause)` in seconds) played tick by
/// tick as ROBOTIS's controller plays them (the Action engine of the CM-510
/// firmware and the DARWIN-OP framework, `Action.cpp`), at 128 ticks a
/// second with the page's inertial force `ease`: each section counts its
/// ticks up, writing an output each; a tick with no output passes to the
/// next section (and, into an ease-in, sets the next step up). Times in
/// units of 8 ms as RoboPlus writes them, played one tick each.
///
/// The ms (from `from_ms`) at which each step's pose is reached (`false`)
/// and at which it stops standing (`true`: the next step set up), and the
/// ms the page ends.
pub fn controller(steps: &[(f64, f64)], ease: u32, from_ms: f64) -> (Vec<(f64, bool)>, f64) {
    const TICK_MS: f64 = 1000.0 / 128.0;
    let units = |seconds: f64| (seconds / 0.008).round() as u32;
    let at = |tick: u32| from_ms + f64::from(tick) * TICK_MS;
    let mut out = Vec::new();
    let (mut section, mut count, mut num) = (Section::Pause, 0u32, 0u32);
    let (mut total, mut accel, mut pause, mut next) = (0u32, 0u32, 0u32, 0usize);
    for tick in 0.. {
        if count < num {
            count += 1;
            // The engine writes the pose itself as the straight part ends (no
            // ease), one tick before the ease-out ends, or on its only tick.
            let reached = match section {
                Section::Straight => accel == 0 && count == num,
                Section::EaseOut => (accel >= 2 && count == num - 1) || (accel == 1 && count == num),
                _ => false,
            };
            if reached {
                out.push((at(tick), false));
            }
            continue;
        }
        count = 0;
        section = match section {
            Section::EaseIn => {
                num = total - 2 * accel;
                Section::Straight
            }
            Section::Straight => {
                num = accel;
                Section::EaseOut
            }
            Section::EaseOut if pause > 0 => {
                num = pause;
                Section::Pause
            }
            Section::EaseOut | Section::Pause => Section::EaseIn,
        };
        if section == Section::EaseIn {
            if next > 0 {
                if total == 0 {
                    // A step that could not ease jumped: its pose is where the next one starts.
                    out.push((at(tick), false));
                }
                out.push((at(tick), true));
            }
            let Some(&(time, step_pause)) = steps.get(next) else { return (out, at(tick)) };
            next += 1;
            (total, accel, pause) = (units(time).max(1), ease, units(step_pause));
            if total <= 2 * accel {
                accel = (total - 1) >> 1;
                if accel == 0 {
                    total = 0;
                }
            }
            num = accel;
        }
    }
    unreachable!("a page ends")
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
        // The controller's times at speed rate 1, divided by the rate
        // (docs/import-export.md); repeat 2: the second pass from the first's end.
        let steps = [(0.496, 0.0), (1.0, 0.296), (0.25, 0.1)];
        let (mut expected, first_pass) = controller(&steps, 32, 0.0);
        expected.extend(controller(&steps, 32, first_pass).0);
        // A stand within one cycle is no frame of its own.
        let mut stood = 0.0;
        let expected: Vec<f64> = expected
            .iter()
            .map(|(ms, is_stand)| (ms / speed, *is_stand))
            .filter(|(ms, is_stand)| {
                // A stand is a frame when it ends on a later cycle than it starts.
                let kept = !is_stand || (ms / Playback::CYCLE_MS).round() > (stood / Playback::CYCLE_MS).round();
                stood = *ms;
                kept
            })
            .map(|(ms, _)| ms)
            .collect();
        assert_eq!(bow.frames.len(), expected.len(), "a frame per move and per pause, both passes: {expected:?}");
        let got = reached(&play, bow.slot, bow.frames.len());
        for (got, want) in got.iter().zip(&expected) {
            assert!(
                (got - want).abs() <= Playback::CYCLE_MS,
                "speed {speed}: reached at {got} ms, RoboPlus at {want} ms"
            );
        }
        // Poses within the unit conversion: the knee's AX units as tenths.
        let knees: Vec<i16> = bow.frames.iter().map(|f| f.values_tenths_deg.get(Joint::RightKneePitch)).collect();
        let pass = [tenths(612), tenths(712), tenths(712), tenths(512), tenths(512)];
        assert_eq!(knees, [pass, pass].concat());
        let first = play.frames.iter().rposition(|a| *a == (bow.slot, 0)).unwrap();
        // What the firmware holds at the end of the move: the frame's value, or a
        // tenth below it (16.16 steps floor: plen2.md §6).
        let held = knee(&play.cycles[first]);
        assert!((tenths(612) - 1..=tenths(612)).contains(&held), "{held}");
        // Repeat 2 played out (no loop: a loop's passes each end a cycle
        // later); next page: a jump to Walk's slot.
        let walk = plen2.motions.iter().find(|m| m.name == "Walk").unwrap();
        assert_eq!(bow.loop_range, None);
        assert_eq!(bow.jump_slot, Some(walk.slot));
        // Exit page: a play list of the page, then its exit page.
        let rest = plen2.motions.iter().find(|m| m.name == "Rest").unwrap();
        let list = plen2.play_lists.iter().find(|l| l.name == "Bow then exit").unwrap();
        assert_eq!(list.entries.iter().map(|e| e.slot).collect::<Vec<_>>(), [bow.slot, rest.slot]);
        assert_eq!(plen2.motions.len(), 3, "the empty page is no motion");
    }
    // Repeat 8: 24 frames do not fit a motion: one loop of every frame, 7 more times.
    let eight = mtn("1.0").replace("play_param=2 3 2 1.0 32", "play_param=2 3 8 1.0 32");
    let (_, _, built) = built(Format::Mtn, &eight, Family::Plen2);
    let bow = built.project.plen2.motions.iter().find(|m| m.name == "Bow").unwrap();
    assert_eq!(bow.loop_range.map(|l| (l.begin_frame, l.end_frame, l.count)), Some((0, 4, 7)));
    assert!(built.report.approximated.iter().any(|n| n.contains("each pass after the first ends one")));
}

#[test]
fn an_mtn_page_on_a_servo_board_is_actions_of_its_play_time_and_delays_of_its_pauses() {
    let (_, _, built) = built(Format::Mtn, &mtn("1.0"), Family::Servo);
    let servo = &built.project.servo;
    let body = servo.macros.iter().find(|m| m.caption == "Bow steps").unwrap();
    // The board's clock after each command: an action's longest step, a delay.
    let mut clock = 0.0;
    let mut board = Vec::new();
    for command in &body.commands {
        match command.run {
            Run::Action { action_id } => {
                let steps = &servo.action(action_id).unwrap().steps;
                clock += steps.iter().map(|s| f64::from(s.interval_10ms) * 10.0).fold(0.0, f64::max);
                let knee = steps.iter().find(|s| s.servo_id == 13).unwrap().degree;
                board.push((clock, Some(knee)));
            }
            Run::Delay { delay_ms } => {
                clock += f64::from(delay_ms);
                board.push((clock, None));
            }
            Run::Macro { .. } => panic!("a page's steps are actions and delays"),
        }
    }
    // Each pose reached and each stand ended within half an update (5 ms) of
    // the controller's time; a stand the board's clock already covers needs no delay.
    let (expected, _) = controller(&[(0.496, 0.0), (1.0, 0.296), (0.25, 0.1)], 32, 0.0);
    let mut board = board.into_iter().peekable();
    let mut knees = Vec::new();
    for (want, is_stand) in expected {
        let got = if is_stand { board.next_if(|(_, knee)| knee.is_none()) } else { board.next() };
        let Some((got, knee)) = got else { continue };
        assert!(
            (got - want).abs() <= 5.0,
            "{} at {want:.1} ms plays at {got} ms",
            if is_stand { "a stand ends" } else { "a pose" }
        );
        knees.extend(knee);
    }
    assert!(board.next().is_none(), "one action per step, a delay per stand at most");
    // 612 AX units is +29.3°: the board's whole degree is 29.
    assert_eq!(knees, [29, 59, 0]);
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
    // Each motion popped from the queue starts on a cycle 0 of its own (plen2.md §6): Wave's
    // keys at 500, 1500 and 2000 ms end on cycles 15, 46 and 61, so it lasts 62 cycles
    // (2,031.6 ms) a pass; Rest's at 1000 ms on cycle 31: 32 cycles (1,048.6 ms). The flow
    // plays 3 × 2,031.6 + 1,048.6 ms for the file's 3 × 2,000 + 1,000: said, +143.5 ms.
    let off = 3.0 * (62.0 * Playback::CYCLE_MS - 2000.0) + (32.0 * Playback::CYCLE_MS - 1000.0);
    let said = format!("\"show\" ends {off:+.1} ms from the file's time");
    assert!(built.report.approximated.iter().any(|n| n.contains(&said)), "{said}: {:?}", built.report.approximated);
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

/// How long a servo board plays macro `id`, ms: each action its longest
/// step, each delay its time, each macro it runs as often as it runs it.
fn macro_ms(servo: &servo_studio::project::ServoProject, id: i32) -> f64 {
    let played = servo.macros.iter().find(|m| m.id == id).unwrap();
    played
        .commands
        .iter()
        .map(|command| match command.run {
            Run::Action { action_id } => {
                let steps = &servo.action(action_id).unwrap().steps;
                steps.iter().map(|s| f64::from(s.interval_10ms) * 10.0).fold(0.0, f64::max)
            }
            Run::Delay { delay_ms } => f64::from(delay_ms),
            Run::Macro { macro_id } => f64::from(command.loop_count.max(1)) * macro_ms(servo, macro_id),
        })
        .sum()
}

/// A chain of next pages plays each page its own repeat count, as RoboPlus's
/// controller does (a page set up from another takes its own repeat), and
/// stops before a page that repeats 0 times: the whole within one board
/// update of the controller's time, worked out page by page here.
#[test]
fn a_chain_of_next_pages_plays_each_page_its_own_repeat_count_and_stops_at_a_page_of_none() {
    let page = |name: &str, next: u32, repeat: u32, steps: &[(&str, &str)]| {
        let steps: String = steps.iter().map(|(pause, time)| step(612, 512, pause, time)).collect();
        format!(
            "page_begin\nname={name}\nplay_param={next} 0 {repeat} 1.0 5\n{steps}{}page_end\n",
            step(512, 512, "0.000", "0.104")
        )
    };
    let enable = format!("enable=0{}\n", " 1".repeat(18));
    let text = format!(
        "type=motion\nversion=1.01\n{enable}motor_type=0\n{}{}{}{}",
        page("Start", 2, 1, &[("0.000", "0.200")]),
        page("Walk", 3, 3, &[("0.048", "0.136"), ("0.000", "0.096")]),
        page("Turn", 4, 2, &[("0.000", "0.304")]),
        page("Never", 0, 0, &[("0.000", "0.504")]),
    );
    let (source, _, built) = built(Format::Mtn, &text, Family::Servo);
    assert!(source.dropped.iter().any(|n| n.contains("repeats 0 times")), "{:?}", source.dropped);
    let servo = &built.project.servo;
    let start = servo.macros.iter().find(|m| m.caption == "Start").unwrap();
    let one = |steps: &[(f64, f64)]| controller(steps, 5, 0.0).1;
    let want = one(&[(0.2, 0.0), (0.104, 0.0)])
        + 3.0 * one(&[(0.136, 0.048), (0.096, 0.0), (0.104, 0.0)])
        + 2.0 * one(&[(0.304, 0.0), (0.104, 0.0)]);
    let got = macro_ms(servo, start.id);
    assert!((got - want).abs() <= 10.0, "the chain plays {got} ms, the controller {want:.1} ms");
}

/// The controller eases each step in and out (the page's inertial force);
/// the conversion moves straight and says how far that strays, worked by
/// hand for "Bow": its last step moves the knee 200 AX units (58.59°) in 31
/// units of time, too short for its ease of 32, so eased over (31 − 1) / 2 =
/// 15 ticks each way. A trapezoid of speed strays from the straight move by
/// at most D·a(T − a) / (2T²) = 58.59 × 15 × 16 / 1,922 = 7.3°.
#[test]
fn how_far_straight_moves_stray_from_the_controllers_eased_ones_is_said() {
    let (source, _, built) = built(Format::Mtn, &mtn("1.0"), Family::Servo);
    let said: Vec<&String> = source.notes.iter().filter(|note| note.contains("inertial force")).collect();
    assert_eq!(said.len(), 1, "{:?}", source.notes);
    assert!(said[0].contains("up to 7.3°") && said[0].contains("(page 1)"), "{}", said[0]);
    assert!(built.report.notes.iter().any(|note| note.contains("up to 7.3°")), "{:?}", built.report.notes);
}

/// An R+ flow of pages whose lengths are no whole number of 10 ms updates
/// (100/128 s = 781.25 ms; 160/128 s = 1,250 ms), played 3 and 2 times, on a
/// servo board: the flow is played out in one macro on one clock, so every
/// pose is reached within half an update (5 ms) of the file's time — the
/// 128ths of a second the format counts, added up here page by page — and
/// the whole within one. (Page macros run one after another each rounded its
/// end to an update: 6.25 ms a pass, 18.75 ms over the flow.)
#[test]
fn an_r_plus_flow_on_a_servo_board_keeps_every_key_on_one_clock() {
    let page = |name: &str, frames: &[(u32, f64)]| {
        let steps: String = frames
            .iter()
            .map(|(frame, elbow)| {
                format!("<step frame=\"{frame}\" pose=\"0 0 0 0 {elbow} 0 0 0 0 0 0 0 0 0 0 0 0 0\" />")
            })
            .collect();
        format!("<Page name=\"{name}\"><steps>{steps}</steps></Page>")
    };
    let text = format!(
        "<?xml version=\"1.0\"?><Root><FlowRoot><Flow name=\"dance\"><units><unit main=\"Step\" mainSpeed=\"1\" loop=\"3\" exit=\"\" /><unit main=\"Sway\" mainSpeed=\"1\" loop=\"2\" exit=\"\" /></units></Flow></FlowRoot><PageRoot>{}{}</PageRoot></Root>",
        page("Step", &[(50, 20.0), (100, 0.0)]),
        page("Sway", &[(60, -25.0), (160, 0.0)]),
    );
    let (_, _, built) = built(Format::Mtnx, &text, Family::Servo);
    let servo = &built.project.servo;
    let dance = servo.macros.iter().find(|m| m.caption == "dance").unwrap();
    // The file's time of each pose: frames in 128ths of a second from each pass's start.
    let mut want = Vec::new();
    let mut start = 0.0;
    for (frames, passes) in [([50.0, 100.0], 3), ([60.0, 160.0], 2)] {
        for _ in 0..passes {
            want.extend(frames.iter().map(|frame| start + frame * 1000.0 / 128.0));
            start += frames[1] * 1000.0 / 128.0;
        }
    }
    let mut clock = 0.0;
    let mut got = Vec::new();
    for command in &dance.commands {
        match command.run {
            Run::Action { action_id } => {
                let steps = &servo.action(action_id).unwrap().steps;
                clock += steps.iter().map(|s| f64::from(s.interval_10ms) * 10.0).fold(0.0, f64::max);
                got.push(clock);
            }
            Run::Delay { delay_ms } => clock += f64::from(delay_ms),
            Run::Macro { .. } => panic!("played out: actions and delays"),
        }
    }
    assert_eq!(got.len(), want.len(), "an action per pose: {got:?} for {want:?}");
    for (got, want) in got.iter().zip(&want) {
        assert!((got - want).abs() <= 5.0, "a pose at {want:.2} ms reached at {got} ms");
    }
    assert!((clock - start).abs() <= 10.0, "the flow ends at {clock} ms, the file's at {start} ms");
}
