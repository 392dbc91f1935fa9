//! Play on board with a sound: a click track played through a real
//! PulseAudio server (a null sink for speakers) while an emulated board,
//! over a pseudo-terminal at its line rate, runs a macro (or the PLEN2 a
//! motion) whose steps fall on the clicks. The null sink's monitor is
//! recorded; each click's time is compared with the board's own start of the
//! matching step.
//!
//! What these tests hold is what works on any machine, however loaded: the
//! board starts, its start is due the link's delay before the sound's point
//! and never goes out early, every click is heard once (waited for by what
//! was recorded, not by the clock) and each falls at its step's place in the
//! show (within half the time between steps). How close the two starts are
//! — within one board update over a minute — is a figure of the machine (an
//! emulator starved by a loaded machine reads the start late, which a board
//! would not): `cargo bench --bench sync` prints it, and the tests print it.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss)]

use std::time::Duration;

use servo_studio::audio::together;
use servo_studio::device::servo::DEFAULT_BAUD;
use servo_studio::protocol::servo::Message;

use crate::common::pulse::{Measured, Pulse, measure_plen2, measure_servo};

/// Clicks a second apart, one a servo board step.
const SERVO_STEPS: usize = 10;

#[test]
fn a_click_track_and_the_boards_steps_start_together_and_every_click_falls_on_its_step() {
    let Some(pulse) = Pulse::start() else { return };
    let measured = measure_servo(&pulse, SERVO_STEPS);
    the_servo_board_started_with_the_sound(&measured);
}

/// The same through `cpal`, the output Windows and macOS use: on Linux it
/// plays into ALSA's default device, which ALSA's PulseAudio plugin sends to
/// the test's server. The plugin finds the server only in the environment,
/// so the playing runs in a process of its own. Built with the `cpal`
/// feature only (its ALSA headers are a system package): `.ci/run` turns it on.
#[cfg(feature = "cpal")]
#[test]
fn through_cpal_a_click_track_and_the_boards_steps_start_together_and_every_click_falls_on_its_step() {
    let Some(pulse) = Pulse::start() else { return };
    let test = "services::sound_sync::through_cpal_in_a_process_of_its_own";
    let said = pulse.in_own_process(&["--exact", test, "--ignored", "--nocapture", "--test-threads=1"]);
    assert!(said.contains("test result: ok. 1 passed"), "{test} ran, alone: {said}");
    assert!(said.contains("cpal sync over"), "the figure is printed: {said}");
    for line in
        said.lines().filter(|line| ["cpal sync", "sent ", "the first click"].iter().any(|s| line.starts_with(s)))
    {
        eprintln!("{line}");
    }
}

#[cfg(feature = "cpal")]
#[test]
#[ignore = "run in a process of its own by the test above"]
fn through_cpal_in_a_process_of_its_own() {
    let pulse = Pulse::of_parent();
    let speakers = servo_studio::audio::output::Speakers::connect_device().unwrap();
    let measured = crate::common::pulse::measure_servo_through(&pulse, SERVO_STEPS, &speakers);
    let worst = the_servo_board_started_with_the_sound(&measured);
    eprintln!("cpal sync over {SERVO_STEPS} s: worst {worst:.2} ms");
}

/// The servo board's start was due the link's delay before the sound's point
/// and every click fell on its own step; the worst offset, ms.
fn the_servo_board_started_with_the_sound(measured: &Measured) -> f64 {
    let command = Message::ExecuteMacroRequest { macro_id: 1 }.encode().unwrap();
    assert_eq!(measured.lead, together::link_delay(command.len(), DEFAULT_BAUD, Duration::ZERO), "the lead");
    every_click_on_its_step(measured, 1000.0)
}

/// Each click at its step's place in the show, nearer it than the next
/// step's or the one before (`spacing_ms` apart); the worst offset from its step, ms.
fn every_click_on_its_step(measured: &Measured, spacing_ms: f64) -> f64 {
    for (step, placed) in measured.placed_ms.iter().enumerate() {
        assert!(
            placed.abs() < spacing_ms / 2.0,
            "step {step}: the click is {placed:.2} ms from its step's place in the show (all: {:?})",
            measured.placed_ms
        );
    }
    let worst = measured.offsets_ms.iter().fold(0.0f64, |worst, offset| worst.max(offset.abs()));
    eprintln!(
        "sync over {} steps: worst {worst:.2} ms; the start went out {:.2} ms after it was due",
        measured.offsets_ms.len(),
        measured.sent_late.as_secs_f64() * 1e3
    );
    worst
}

#[test]
fn a_click_track_and_a_plen2_motions_frames_start_together_and_every_click_falls_on_its_frame() {
    let Some(pulse) = Pulse::start() else { return };
    // 8 frames of a second.
    let measured = measure_plen2(&pulse, 8, 1000);
    let delay = servo_studio::device::plen2::play_motion_delay(0, Duration::ZERO);
    assert_eq!(measured.lead, delay, "the lead: the command's time on the line and half a cycle");
    every_click_on_its_step(&measured, 1000.0);
}
