//! `servo-studio play` with its sound through a real PulseAudio server (a
//! null sink for speakers): two servo boards and a PLEN2 behind the bursty
//! Bluetooth-like bridge, each cued on a click of the show's sound, each
//! emulator logging what it takes in on the system's monotonic clock. The
//! null sink's monitor is recorded; each click's time is compared with the
//! moment its board took its start in. Held here (on any machine, however
//! loaded): the show plays with its sound, every board starts, and each
//! start falls on its own click (within half the clicks' spacing); how close
//! is printed (docs/show.md gives the figures).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_precision_loss)]

use std::process::Stdio;
use std::time::{Duration, Instant};

use servo_studio::project::SoundTrack;
use servo_studio::show::{Cue, Show, Start};
use servo_studio::sim::MonotonicClock;

use crate::cli::play::{Stage, device, first, logged_until, swinging, waving};
use crate::common::pulse::{Pulse, RATE, Recorder, clicks};

#[test]
fn a_show_starts_every_board_on_its_click_of_the_sound() {
    let Some(pulse) = Pulse::start() else { return };
    let at_s = [0.0, 1.0, 2.0];
    let show = Show {
        devices: vec![device("a", swinging(1)), device("b", swinging(1)), device("plen", waving())],
        sound: Some(SoundTrack {
            path: "clicks.wav".into(),
            duration_ms: 3000,
            sha256: String::new(),
            offset_ms: 0,
            sensitivity_percent: 50,
        }),
        cues: vec![
            Cue { device: "a".into(), at_ms: 0, start: Start::Macro(1) },
            Cue { device: "b".into(), at_ms: 1000, start: Start::Macro(1) },
            Cue { device: "plen".into(), at_ms: 2000, start: Start::Slot(2) },
        ],
    };
    let stage = Stage::new(&show, &[("plen", &["--link", "bursty"])]);
    std::fs::write(stage.dir.path().join("clicks.wav"), servo_studio::audio::pcm16_wav(&clicks(&at_s, 3.0), RATE, 1))
        .unwrap();
    let recorder = Recorder::start(&pulse);
    let folder = pulse.socket.parent().unwrap();
    // In an environment naming the server, as a user's session does.
    let mut args = vec!["play".to_string(), stage.dir.path().join("show.json").display().to_string()];
    args.extend(stage.device_args());
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_servo-studio"))
        .args(&args)
        .env("PULSE_SERVER", format!("unix:{}", pulse.socket.display()))
        .env("HOME", folder)
        .env("XDG_RUNTIME_DIR", folder)
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let (said, stderr) = (String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    assert!(said.contains("with its sound"), "the show played its sound: {said}\n{stderr}");
    let heard = recorder.clicks(3, Instant::now(), Duration::from_secs(60));
    let clock = MonotonicClock::now();
    let took_in = [
        first(&logged_until(stage.log("a"), "ExecuteMacroRequest", Duration::from_secs(10)), "ExecuteMacroRequest"),
        first(&logged_until(stage.log("b"), "ExecuteMacroRequest", Duration::from_secs(10)), "ExecuteMacroRequest"),
        first(&logged_until(stage.log("plen"), "$PM02", Duration::from_secs(10)), "$PM02"),
    ];
    for ((name, click), board) in ["a", "b", "plen"].iter().zip(&heard).zip(took_in) {
        let off_ms = (board as f64 - clock.ns(*click) as f64) / 1e6;
        eprintln!("figures: {name} took its start in {off_ms:+.2} ms from its click");
        assert!(off_ms.abs() < 500.0, "{name}: {off_ms:.1} ms from its click, the clicks are 1 s apart");
    }
}
