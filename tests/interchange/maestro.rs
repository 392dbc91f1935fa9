//! Maestro settings files: frames move each channel at its speed limit
//! ((¼ µs) per 10 ms; 0 = as fast as the servo goes) and the next frame starts
//! after the frame's duration (Pololu's Maestro user's guide, "Sequencer").
//! Figures below are worked out by hand from that rule and from the
//! conversion 1500 µs = 0°, 10 µs a degree (docs/import-export.md).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::float_cmp)]

use servo_studio::interchange::{Format, export};
use servo_studio::project::{self, Family, Run};

use super::built;

/// Channel 0 "jaw" at speed 20, channel 1 a digital output, channel 2 "neck"
/// at speed 0, channel 3 "eye" at speed 10; every frame's moves finish
/// within the frame (so the board can express it exactly).
pub const SETTINGS: &str = r#"<!--Pololu Maestro servo controller settings file, http://www.pololu.com/catalog/product/1350-->
<UscSettings version="1">
  <NeverSuspend>false</NeverSuspend>
  <SerialMode>UART_FIXED_BAUD_RATE</SerialMode>
  <FixedBaudRate>9600</FixedBaudRate>
  <Channels ServosAvailable="6" ServoPeriod="156">
    <!--Channel 0-->
    <Channel name="jaw 下巴" mode="Servo" min="3968" max="8000" homemode="Goto" home="6000" speed="20" acceleration="0" neutral="6000" range="1905" />
    <Channel name="" mode="Output" min="3968" max="8000" homemode="Off" home="3968" speed="0" acceleration="0" neutral="6000" range="1905" />
    <Channel name="neck" mode="Servo" min="4000" max="8000" homemode="Goto" home="6000" speed="0" acceleration="0" neutral="6000" range="1905" />
    <Channel name="eye" mode="Servo" min="4000" max="8000" homemode="Goto" home="6000" speed="10" acceleration="0" neutral="6000" range="1905" />
  </Channels>
  <Sequences>
    <Sequence name="talk">
      <Frame name="Frame 0" duration="500">6400 0 5600 6000</Frame>
      <Frame name="Frame 1" duration="250">6000 0 6000 6200</Frame>
      <Frame name="Frame 2" duration="1000">7200 0 6800 6000</Frame>
    </Sequence>
    <Sequence name="blink">
      <Frame name="shut" duration="300">6000 0 6000 6240</Frame>
      <Frame name="open" duration="700">6000 0 6000 6000</Frame>
    </Sequence>
  </Sequences>
  <Script ScriptDone="true"></Script>
</UscSettings>"#;

/// A frame: its duration and each servo channel's target but those at 0, by channel.
type Frame = (f64, Vec<(String, f64)>);

/// Each sequence's frames.
fn frames(text: &str) -> Vec<(String, Vec<Frame>)> {
    let source = servo_studio::interchange::read(Format::Maestro, text).unwrap();
    source
        .clips
        .iter()
        .map(|clip| {
            let servo_studio::interchange::Body::Keys(keys) = &clip.body else { panic!("frames") };
            let frames = keys
                .iter()
                .map(|key| {
                    let servo_studio::interchange::Timing::Frame { duration_ms } = key.timing else {
                        panic!("a frame")
                    };
                    let targets = source
                        .channels
                        .iter()
                        .zip(&key.values)
                        .filter_map(|(channel, v)| Some((channel.key.clone(), (*v)?)))
                        .collect();
                    (duration_ms, targets)
                })
                .collect();
            (clip.name.clone(), frames)
        })
        .collect()
}

#[test]
fn settings_to_a_project_and_back_keep_every_frame_exactly() {
    let (_, map, built) = built(Format::Maestro, SETTINGS, Family::Servo);
    let (written, report) = export::maestro(&built.project.servo, Some(&map)).unwrap();
    assert_eq!(frames(&written), frames(SETTINGS), "{written}");
    assert!(report.converted[0].starts_with("3 channels, 2 sequences, 5 frames"), "{report:?}");
    // The channels keep their names (CJK too) and homes.
    assert!(written.contains(r#"name="jaw 下巴""#) && written.contains(r#"home="6000""#), "{written}");
}

#[test]
fn each_channel_moves_at_its_speed_limit_and_the_next_frame_waits_for_the_duration() {
    let (_, _, built) = built(Format::Maestro, SETTINGS, Family::Servo);
    let servo = &built.project.servo;
    let talk = servo.macros.iter().find(|m| m.caption == "talk").unwrap();
    let (trajectories, end_ms) = project::trace(servo, Run::Macro { macro_id: talk.id }, 60_000.0).unwrap();
    let angle = |servo_id: u8, ms: f64| project::angle_at(&trajectories[&servo_id], ms).unwrap();
    // Jaw: 6000 → 6400 is 400 ¼ µs at 20 per 10 ms: 200 ms, to +10°.
    assert_eq!(angle(0, 100.0), 5.0);
    assert_eq!(angle(0, 200.0), 10.0);
    assert_eq!(angle(0, 499.0), 10.0, "it waits for the frame to end");
    // Frame 1 starts at 500 ms: back to 0° in another 200 ms.
    assert_eq!(angle(0, 600.0), 5.0);
    assert_eq!(angle(0, 700.0), 0.0);
    // Eye: 6000 → 6200 at 10 per 10 ms: 200 ms from 500 ms, to +5°.
    assert_eq!(angle(3, 600.0), 2.5);
    // Frame 2 at 750 ms: jaw 6000 → 7200, 1200 at 20: 600 ms, to +30°.
    assert_eq!(angle(0, 1050.0), 15.0);
    assert_eq!(angle(0, 1350.0), 30.0);
    assert_eq!(end_ms, 1750.0, "500 + 250 + 1000 ms");
}

#[test]
fn a_channel_at_speed_0_moves_at_the_live_speed_limit_and_never_slams() {
    let (_, _, built) = built(Format::Maestro, SETTINGS, Family::Servo);
    let first = &built.project.servo.actions[0];
    let neck = first.steps.iter().find(|step| step.servo_id == 2).unwrap();
    // 6000 → 5600 is −10°: at 180°/s that is 55.6 ms, 6 updates.
    assert_eq!((neck.degree, neck.interval_10ms), (-10, 6));
    assert!(!built.report.approximated.iter().any(|n| n.contains("shorter")), "{:?}", built.report);
}

#[test]
fn a_frame_too_short_for_the_speed_limit_ends_where_the_maestro_gets_the_servo() {
    let short =
        SETTINGS.replace(r#"<Frame name="Frame 0" duration="500">"#, r#"<Frame name="Frame 0" duration="100">"#);
    let (_, _, built) = built(Format::Maestro, &short, Family::Servo);
    let jaw = built.project.servo.actions[0].steps.iter().find(|step| step.servo_id == 0).unwrap();
    // 100 ms of a 200 ms move: half way, +5°, in 10 updates.
    assert_eq!((jaw.degree, jaw.interval_10ms), (5, 10));
    assert!(
        built.report.approximated.iter().any(|note| note.contains("shorter than a channel's speed limit")),
        "{:?}",
        built.report
    );
}

#[test]
fn names_limits_and_homes_become_the_servos_own() {
    let (_, _, built) = built(Format::Maestro, SETTINGS, Family::Servo);
    let servos = &built.project.servo.servos;
    assert_eq!(servos.iter().map(|s| s.id).collect::<Vec<_>>(), [0, 2, 3], "the output channel is no servo");
    assert_eq!(servos[0].caption, "jaw 下巴");
    // 3968 ¼ µs is −50.8°: rounded inward, −50°; 8000 is +50°.
    assert_eq!((servos[0].min_deg, servos[0].max_deg, servos[0].home_deg), (-50, 50, 0));
    assert!(built.report.dropped.iter().any(|note| note.contains("channel 1 (Output)")));
    assert!(built.report.dropped.iter().filter(|note| note.contains("a target of 0")).count() == 1, "said once");
}

#[test]
fn malformed_settings_files_say_where() {
    let read = |text: &str| servo_studio::interchange::read(Format::Maestro, text).unwrap_err().to_string();
    let cut = read(&SETTINGS[..SETTINGS.find("<Frame name=\"Frame 2\"").unwrap()]);
    assert!(cut.contains("never closed"), "{cut}");
    assert!(read("<Settings version=\"1\"/>").contains("not <UscSettings>"));
    let word = read(&SETTINGS.replace("duration=\"250\"", "duration=\"soon\""));
    assert!(word.starts_with("line 16: <Frame>: duration \"soon\" is not a number"), "{word}");
    let target = read(&SETTINGS.replace("6000 0 6000 6200", "6000 0 six 6200"));
    assert!(target.starts_with("line 16: <Frame>: target \"six\""), "{target}");
}
