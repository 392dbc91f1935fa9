//! Play on board with a sound: a click track played through a real
//! PulseAudio server (a null sink for speakers) while the emulated board,
//! over a pseudo-terminal at its line rate, runs a macro whose steps fall on
//! the clicks. The null sink's monitor is recorded; each click's time is
//! compared with the board's own start of the matching step. Every offset
//! must be within one board update (10 ms) over a whole minute.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss)]

use crate::common::pulse::{Pulse, measure_plen2, measure_servo};

#[test]
fn a_click_track_and_the_boards_steps_stay_within_one_board_update_over_a_minute() {
    let Some(pulse) = Pulse::start() else { return };
    let measured = measure_servo(&pulse, 60);
    let worst = measured.offsets_ms.iter().fold(0.0f64, |worst, offset| worst.max(offset.abs()));
    for (step, offset) in measured.offsets_ms.iter().enumerate() {
        assert!(
            offset.abs() <= 10.0,
            "step {step}: the click is {offset:.2} ms from the board's step (all: {:?})",
            measured.offsets_ms
        );
    }
    eprintln!("sync over 60 s: worst {worst:.2} ms");
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
