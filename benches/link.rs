//! Link benchmarks (prints figures; run with `cargo bench --bench link`):
//! 1. 1,000 request/response round trips with the emulated board behind a
//!    pseudo-terminal: median and tail round-trip times.
//! 2. Export and import of a rich project through a link throttled to
//!    115200 baud: elapsed time against the pure wire time of the bytes exchanged.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_possible_truncation, missing_docs)]

#[path = "../tests/common/mod.rs"]
mod common;

use std::time::{Duration, Instant};

use servo_studio::device::Cancel;
use servo_studio::device::servo::DEFAULT_BAUD;
use servo_studio::device::servo::{
    ImportOptions, ServoBoard, ServoEvent, ServoImage, SessionConfig, Traffic, export, import,
};
use servo_studio::link::{LinkEvent, PortName, no_waker};
use servo_studio::project::ServoProject;
use servo_studio::protocol::servo::Message;
use servo_studio::sim::{ServoSim, SimConfig, SimHandle};

fn start(config: SimConfig, preload: &ServoProject) -> SimHandle {
    let sim = ServoSim::new(config, ServoImage::from_project(preload).unwrap());
    #[cfg(unix)]
    let handle = servo_studio::sim::spawn_pty(sim, no_waker()).unwrap();
    #[cfg(not(unix))]
    let handle = servo_studio::sim::spawn_tcp(sim, "127.0.0.1:0".parse().unwrap(), no_waker()).unwrap();
    handle
}

fn connect(sim: &SimHandle, traffic: bool) -> ServoBoard {
    let config = SessionConfig { traffic, response_timeout: Duration::from_secs(5), ..SessionConfig::default() };
    ServoBoard::connect(&PortName::parse(&sim.port_name).unwrap(), DEFAULT_BAUD, config, no_waker()).unwrap()
}

fn percentile(sorted: &[Duration], fraction: f64) -> Duration {
    let index = ((sorted.len() - 1) as f64 * fraction).round() as usize;
    sorted[index]
}

fn round_trips() {
    let sim = start(SimConfig::default(), &ServoProject::default());
    let board = connect(&sim, false);
    let requester = board.requester();
    for _ in 0..50 {
        requester.request(Message::QueryProjectIdRequest).unwrap();
    }
    let mut times: Vec<Duration> = (0..1000)
        .map(|_| {
            let began = Instant::now();
            requester.request(Message::QueryProjectIdRequest).unwrap();
            began.elapsed()
        })
        .collect();
    times.sort_unstable();
    let mean = times.iter().sum::<Duration>() / 1000;
    println!(
        "round trip over {}: 1000 requests, median {:.1} µs, p90 {:.1} µs, p99 {:.1} µs, max {:.1} µs, mean {:.1} µs",
        sim.port_name,
        percentile(&times, 0.5).as_secs_f64() * 1e6,
        percentile(&times, 0.9).as_secs_f64() * 1e6,
        percentile(&times, 0.99).as_secs_f64() * 1e6,
        times[999].as_secs_f64() * 1e6,
        mean.as_secs_f64() * 1e6,
    );
}

/// Bytes that crossed the link in either direction, from the packet log.
fn bytes_exchanged(board: &ServoBoard) -> usize {
    board
        .events()
        .try_iter()
        .map(|event| match event {
            LinkEvent::Driver(ServoEvent::Traffic(Traffic::Sent { frame, .. } | Traffic::Received { frame, .. })) => {
                frame.wire_len()
            }
            LinkEvent::Driver(ServoEvent::Traffic(Traffic::Skipped { bytes, .. })) => bytes,
            _ => 0,
        })
        .sum()
}

fn report(name: &str, elapsed: Duration, bytes: usize) {
    let wire = Duration::from_secs_f64(bytes as f64 * 10.0 / f64::from(DEFAULT_BAUD));
    println!(
        "{name} at 115200 baud: {bytes} bytes exchanged, wire time {:.1} ms, elapsed {:.1} ms, ratio {:.3}",
        wire.as_secs_f64() * 1e3,
        elapsed.as_secs_f64() * 1e3,
        elapsed.as_secs_f64() / wire.as_secs_f64()
    );
}

fn throttled_transfers() {
    let rich = common::rich_project();
    let config = SimConfig { baud: Some(DEFAULT_BAUD), ..SimConfig::default() };

    let sim = start(config.clone(), &rich);
    let board = connect(&sim, true);
    let began = Instant::now();
    let exported = export(&board.requester(), &mut |_| {}, &Cancel::never()).unwrap();
    let elapsed = began.elapsed();
    assert_eq!(exported, common::exported(rich.clone()));
    report("export", elapsed, bytes_exchanged(&board));

    let sim = start(config, &ServoProject::default());
    let board = connect(&sim, true);
    let options = ImportOptions { backup_dir: None, verify: false, force: false };
    let began = Instant::now();
    import(&board.requester(), &rich, &options, &mut |_| {}, &Cancel::never()).unwrap();
    let elapsed = began.elapsed();
    report("import (no backup, no verify)", elapsed, bytes_exchanged(&board));
}

fn main() {
    round_trips();
    throttled_transfers();
}
