//! The sound's output through `cpal` (what Windows and macOS use) played in
//! step with an emulated board, as `services::sound_sync` plays it through
//! the default output. A test binary of its own, built with the `cpal`
//! feature only (its ALSA headers are a system package): `.ci/run` builds it,
//! so the suite is not built a second time with the feature on.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss)]
// The helpers are the suite's; this binary uses a few of them.
#![allow(dead_code)]

#[path = "common/pulse.rs"]
mod pulse;

use pulse::{Pulse, SERVO_STEPS, the_servo_board_started_with_the_sound};

/// No sound server here: a failure where services are required (CI,
/// SERVO_STUDIO_REQUIRE_SERVICES), else a skip saying what to install — as
/// the suite's `common::without_service`, which `pulse` asks for.
fn without_service(what: &str, install: &str) {
    let set = |name: &str| std::env::var(name).is_ok_and(|value| !value.is_empty() && value != "0" && value != "false");
    assert!(
        !(set("CI") || set("SERVO_STUDIO_REQUIRE_SERVICES")),
        "{what} (CI / SERVO_STUDIO_REQUIRE_SERVICES require it): {install}"
    );
    eprintln!("skipped: {what}; to run it: {install}");
}

/// The same through `cpal`, the output Windows and macOS use: on Linux it
/// plays into ALSA's default device, which ALSA's PulseAudio plugin sends to
/// the test's server. The plugin finds the server only in the environment,
/// so the playing runs in a process of its own. Built with the `cpal`
/// feature only (its ALSA headers are a system package): `.ci/run` turns it on.
#[test]
fn through_cpal_a_click_track_and_the_boards_steps_start_together_and_every_click_falls_on_its_step() {
    let Some(pulse) = Pulse::start() else { return };
    let test = "through_cpal_in_a_process_of_its_own";
    let said = pulse.in_own_process(&["--exact", test, "--ignored", "--nocapture", "--test-threads=1"]);
    assert!(said.contains("test result: ok. 1 passed"), "{test} ran, alone: {said}");
    assert!(said.contains("cpal sync over"), "the figure is printed: {said}");
    for line in
        said.lines().filter(|line| ["cpal sync", "sent ", "the first click"].iter().any(|s| line.starts_with(s)))
    {
        eprintln!("{line}");
    }
}

#[test]
#[ignore = "run in a process of its own by the test above"]
fn through_cpal_in_a_process_of_its_own() {
    let pulse = Pulse::of_parent();
    let speakers = servo_studio::audio::output::Speakers::connect_device().unwrap();
    let measured = pulse::measure_servo_through(&pulse, SERVO_STEPS, &speakers);
    let worst = the_servo_board_started_with_the_sound(&measured);
    eprintln!("cpal sync over {SERVO_STEPS} s: worst {worst:.2} ms");
}
