//! Sound and board together: a one-minute click track played through a real
//! PulseAudio server (null sink) while the emulated servo board, over a
//! pseudo-terminal, runs a macro with a step on each click. Prints how far
//! each click was from its step (the test holds every one within 10 ms, one
//! board update). Needs Debian's `pulseaudio` (`.ci/run` installs it).
//!
//! `cargo bench --bench sync`

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss, missing_docs)]

#[path = "../tests/common/pulse.rs"]
mod pulse;

fn main() {
    let Some(server) = pulse::Pulse::start() else {
        println!("sync: skipped (no pulseaudio)");
        return;
    };
    let steps = 60;
    let measured = pulse::measure_servo(&server, steps);
    let offsets = &measured.offsets_ms;
    let worst = offsets.iter().fold(0.0f64, |worst, offset| worst.max(offset.abs()));
    let mean = offsets.iter().sum::<f64>() / offsets.len() as f64;
    let (low, high) =
        offsets.iter().fold((f64::MAX, f64::MIN), |(low, high), offset| (low.min(*offset), high.max(*offset)));
    println!(
        "sync, servo board over a pty, {steps} clicks over {steps} s: worst {worst:.2} ms, mean {mean:+.2} ms, \
         from {low:+.2} to {high:+.2} ms (drift over the minute {:+.3} ms); one board update is 10 ms",
        offsets[offsets.len() - 1] - offsets[0]
    );
}
