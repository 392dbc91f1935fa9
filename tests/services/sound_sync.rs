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

use crate::common::pulse::{
    Pulse, SERVO_STEPS, every_click_on_its_step, measure_plen2, measure_servo, the_servo_board_started_with_the_sound,
};

#[test]
fn a_click_track_and_the_boards_steps_start_together_and_every_click_falls_on_its_step() {
    let Some(pulse) = Pulse::start() else { return };
    let measured = measure_servo(&pulse, SERVO_STEPS);
    the_servo_board_started_with_the_sound(&measured);
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
