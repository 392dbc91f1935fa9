//! Sound and board together: a one-minute click track played through a real
//! PulseAudio server (null sink) while the emulated servo board, over a
//! pseudo-terminal, runs a macro with a step on each click; then the same
//! with the emulated PLEN2 playing a motion with a click on each frame. Prints how far
//! each click was from its step (the test holds every one within 10 ms, one
//! board update). The servo minute is played twice: through the sound
//! server's own protocol (Linux), and through cpal (the output Windows and
//! macOS use), here into ALSA's default device, which ALSA's PulseAudio
//! plugin sends to the same server. Needs Debian's `pulseaudio`; the cpal
//! minute is played only when the bench is built with the `cpal` feature,
//! which needs `libasound2-dev` to build and `libasound2-plugins` to play
//! (`.ci/run` installs them).
//!
//! `cargo bench --bench sync [--features cpal]`

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss, missing_docs)]

#[path = "../tests/common/pulse.rs"]
mod pulse;

/// What `pulse` calls when its server cannot be started: the bench says so and skips.
fn without_service(what: &str, install: &str) {
    println!("sync: skipped: {what}; to run it: {install}");
}

/// This bench run again to play through cpal (see `main`).
const THROUGH_CPAL: &str = "through-cpal";

fn main() {
    #[cfg(feature = "cpal")]
    if std::env::args().any(|arg| arg == THROUGH_CPAL) {
        // In a process of its own, whose environment names the server for ALSA's PulseAudio plugin.
        let server = pulse::Pulse::of_parent();
        let speakers = servo_studio::audio::output::Speakers::connect_device().unwrap();
        let servo = pulse::measure_servo_through(&server, 60, &speakers);
        say("servo board over a pty, 60 clicks over 60 s, through cpal (ALSA)", &servo.offsets_ms, 10.0);
        return;
    }
    let Some(server) = pulse::Pulse::start() else { return };
    let steps = 60;
    let servo = pulse::measure_servo(&server, steps);
    say(&format!("servo board over a pty, {steps} clicks over {steps} s"), &servo.offsets_ms, 10.0);
    // The output Windows and macOS use, here into ALSA's PulseAudio plugin.
    if cfg!(feature = "cpal") {
        print!("{}", server.in_own_process(&[THROUGH_CPAL]));
    } else {
        println!("sync through cpal: not built (cargo bench --bench sync --features cpal; needs libasound2-dev)");
    }
    let plen2 = pulse::measure_plen2(&server, 20, 3000);
    say("PLEN2 over a pty, a motion of 20 frames of 3 s (a click on each frame)", &plen2.offsets_ms, 32.768);
}

fn say(what: &str, offsets: &[f64], update_ms: f64) {
    let worst = offsets.iter().fold(0.0f64, |worst, offset| worst.max(offset.abs()));
    let mean = offsets.iter().sum::<f64>() / offsets.len() as f64;
    let (low, high) =
        offsets.iter().fold((f64::MAX, f64::MIN), |(low, high), offset| (low.min(*offset), high.max(*offset)));
    println!(
        "sync, {what}: worst {worst:.2} ms, mean {mean:+.2} ms, from {low:+.2} to {high:+.2} ms \
         (drift over the minute {:+.3} ms); one board update is {update_ms} ms",
        offsets[offsets.len() - 1] - offsets[0]
    );
}
