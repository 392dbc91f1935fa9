//! rFLEX driving figures, over a pseudo-terminal against the emulated base:
//! the command cadence while a velocity is held (against the 100 ms of the
//! reference drivers), the time from a release / STOP to the stop frame
//! arriving at the base, and the same from a gamepad's dead-man released on a
//! named pipe read by `rflex teleop`.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::print_stdout, clippy::cast_possible_truncation)]

use std::time::{Duration, Instant};

use servo_studio::device::rflex::RflexBase;
use servo_studio::link::{LinkEvent, PortName, no_waker};
use servo_studio::project::Family;
use servo_studio::protocol::rflex::{B21R, Command};
use servo_studio::sim::{RflexSim, RflexSimConfig, RflexSimEvent, spawn_pty};

fn percentile(sorted: &[Duration], p: f64) -> Duration {
    let index = ((sorted.len() - 1) as f64 * p).round() as usize;
    sorted[index]
}

/// The translation speed of an axis-0 command the base received, if that is what `event` is.
fn translation(event: &LinkEvent<RflexSimEvent>) -> Option<u32> {
    match event {
        LinkEvent::Driver(RflexSimEvent::Received(Command::AxisSetDir { axis: 0, speed, .. })) => Some(*speed),
        _ => None,
    }
}

/// Waits until the base receives a translation command whose speed `wanted` picks.
fn received(events: &crossbeam_channel::Receiver<LinkEvent<RflexSimEvent>>, what: &str, wanted: impl Fn(u32) -> bool) {
    loop {
        let event = events.recv_timeout(Duration::from_secs(10)).unwrap_or_else(|_| panic!("{what} never arrived"));
        if translation(&event).is_some_and(&wanted) {
            return;
        }
    }
}

/// Prints the median, p90 and worst of `latencies`, after `what`.
fn print_latencies(what: &str, latencies: &mut [Duration]) {
    latencies.sort();
    println!(
        "{what}: median {:.2} ms, p90 {:.2} ms, worst {:.2} ms",
        percentile(latencies, 0.5).as_secs_f64() * 1e3,
        percentile(latencies, 0.9).as_secs_f64() * 1e3,
        latencies.last().unwrap().as_secs_f64() * 1e3
    );
}

fn main() {
    let sim = spawn_pty(RflexSim::new(RflexSimConfig::default()), no_waker()).unwrap();
    let port = PortName::parse(&sim.port_name).unwrap();
    let settings = servo_studio::device::line_settings(Family::Rflex);
    let mut base = RflexBase::over(servo_studio::link::open(&port, &settings).unwrap(), B21R, no_waker()).unwrap();
    base.start(false);
    base.set_brake(false);
    let events = sim.events().clone();

    // Cadence: 5 s of a held velocity; when each translation frame arrives.
    base.drive(0.4, 0.1, 0.5);
    let began = Instant::now();
    let mut arrivals = Vec::new();
    while began.elapsed() < Duration::from_secs(5) {
        if let Ok(event) = events.recv_timeout(Duration::from_millis(500))
            && translation(&event).is_some()
        {
            arrivals.push(Instant::now());
        }
        base.pump(Instant::now());
    }
    let mut gaps: Vec<Duration> = arrivals.windows(2).map(|pair| pair[1] - pair[0]).collect();
    gaps.sort();
    println!(
        "cadence while driving over {}: {} commands in 5 s, interval median {:.1} ms, p90 {:.1} ms, worst {:.1} ms (target 100 ms)",
        sim.port_name,
        arrivals.len(),
        percentile(&gaps, 0.5).as_secs_f64() * 1e3,
        percentile(&gaps, 0.9).as_secs_f64() * 1e3,
        gaps.last().unwrap().as_secs_f64() * 1e3
    );

    // Release / STOP to the stop frame at the base, 50 times.
    let mut latencies = Vec::new();
    for _ in 0..50 {
        base.drive(0.3, 0.0, 0.5);
        // Wait for the drive to arrive, so the stop is the next thing on the wire.
        received(&events, "the drive", |speed| speed > 0);
        let pressed = Instant::now();
        base.stop();
        received(&events, "the stop", |speed| speed == 0);
        latencies.push(pressed.elapsed());
        base.pump(Instant::now());
    }
    print_latencies("release / STOP → stop frame at the base, 50 times", &mut latencies);
    gamepad_release();
}

/// `rflex teleop` reading a named pipe of input events, as a gamepad forwarded
/// over a pipe is read: the time from the dead-man's release written to the
/// pipe to the stop frame arriving at the base, 50 times.
fn gamepad_release() {
    use servo_studio::gamepad::{ABS_Y, BTN_TL, RawEvent};
    use std::io::Write;
    let sim = spawn_pty(RflexSim::new(RflexSimConfig::default()), no_waker()).unwrap();
    let folder = tempfile::tempdir().unwrap();
    let fifo = folder.path().join("pad");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let mut teleop = std::process::Command::new(env!("CARGO_BIN_EXE_servo-studio"))
        .args(["rflex", "teleop", "--port", &sim.port_name, "--gamepad", fifo.to_str().unwrap(), "--speed", "0.4"])
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let mut pipe = std::fs::OpenOptions::new().write(true).open(&fifo).unwrap();
    let mut frame = |events: &[RawEvent]| {
        let mut bytes: Vec<u8> = events.iter().flat_map(|event| event.to_bytes(0)).collect();
        bytes.extend(RawEvent::report().to_bytes(0));
        pipe.write_all(&bytes).unwrap();
        Instant::now()
    };
    let events = sim.events().clone();
    let mut latencies = Vec::new();
    for _ in 0..50 {
        frame(&[RawEvent::key(BTN_TL, true), RawEvent::abs(ABS_Y, -32768)]);
        received(&events, "the drive", |speed| speed > 0);
        let released = frame(&[RawEvent::key(BTN_TL, false)]);
        received(&events, "the stop", |speed| speed == 0);
        latencies.push(released.elapsed());
    }
    let _ = teleop.kill();
    let _ = teleop.wait();
    print_latencies(
        "gamepad dead-man released on a pipe → stop frame at the base (rflex teleop), 50 times (target: median under 15 ms)",
        &mut latencies,
    );
}
