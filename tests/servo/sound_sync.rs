//! Play on board with a sound: a click track played through a real
//! PulseAudio server (a null sink for speakers) while the emulated board,
//! over a pseudo-terminal at its line rate, runs a macro whose steps fall on
//! the clicks. The null sink's monitor is recorded; each click's time is
//! compared with the board's own start of the matching step. Every offset
//! must be within one board update (10 ms) over a whole minute.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss)]

use crate::common::pulse::{Measured, Pulse, measure_plen2, measure_servo, measure_servo_through};

#[test]
fn a_click_track_and_the_boards_steps_stay_within_one_board_update_over_a_minute() {
    let Some(pulse) = Pulse::start() else { return };
    let worst = within_one_servo_update(&measure_servo(&pulse, 60));
    eprintln!("sync over 60 s: worst {worst:.2} ms");
}

/// The same minute through `cpal`, the output Windows and macOS use: on
/// Linux it plays into ALSA's default device, which ALSA's PulseAudio plugin
/// sends to the test's server. The plugin finds the server only in the
/// environment, so the playing runs in a process of its own.
#[test]
fn through_cpal_a_click_track_and_the_boards_steps_stay_within_one_board_update_over_a_minute() {
    let Some(pulse) = Pulse::start() else { return };
    let test = "servo::sound_sync::through_cpal_in_a_process_of_its_own";
    let said = pulse.in_own_process(&["--exact", test, "--ignored", "--nocapture", "--test-threads=1"]);
    assert!(said.contains("test result: ok. 1 passed"), "{test} ran, alone: {said}");
    assert!(said.contains("cpal sync over 60 s"), "the figure is printed: {said}");
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
    let worst = within_one_servo_update(&measure_servo_through(&pulse, 60, &speakers));
    eprintln!("cpal sync over 60 s: worst {worst:.2} ms");
}

/// Every click within one servo board update (10 ms) of its step; the worst, ms.
fn within_one_servo_update(measured: &Measured) -> f64 {
    for (step, offset) in measured.offsets_ms.iter().enumerate() {
        assert!(
            offset.abs() <= 10.0,
            "step {step}: the click is {offset:.2} ms from the board's step (all: {:?})",
            measured.offsets_ms
        );
    }
    measured.offsets_ms.iter().fold(0.0f64, |worst, offset| worst.max(offset.abs()))
}

#[test]
fn a_click_track_and_a_plen2_motions_frames_stay_within_one_robot_update_over_a_minute() {
    let Some(pulse) = Pulse::start() else { return };
    // 20 frames of 3 s: a motion's most, a minute.
    let measured = measure_plen2(&pulse, 20, 3000);
    let update_ms = servo_studio::device::plen2::playback::Playback::CYCLE_MS;
    for (frame, offset) in measured.offsets_ms.iter().enumerate() {
        assert!(
            offset.abs() <= update_ms,
            "frame {frame}: the click is {offset:.2} ms from the robot's frame (all: {:?})",
            measured.offsets_ms
        );
    }
    let worst = measured.offsets_ms.iter().fold(0.0f64, |worst, offset| worst.max(offset.abs()));
    eprintln!("PLEN2 sync over 60 s: worst {worst:.2} ms");
}
