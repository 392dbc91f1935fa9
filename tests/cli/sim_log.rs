//! `servo-studio sim --log FILE`: every command the emulated board takes in,
//! a line each, the system's monotonic clock in nanoseconds first — the
//! clock this test reads too, so each line's time falls between the moment
//! the test wrote the command and the moment it read the line (any family).

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::io::Write;
use std::path::Path;
use std::time::{Duration, Instant};

use servo_studio::protocol::rflex::Command as RflexCommand;
use servo_studio::protocol::servo::Message;
use servo_studio::sim::MonotonicClock;

use crate::common;

/// The log's lines once it has `count`, waiting on the file itself (bounded).
fn lines(path: &Path, count: usize) -> Vec<(u128, String)> {
    let deadline = Instant::now() + Duration::from_secs(30);
    loop {
        let text = std::fs::read_to_string(path).unwrap_or_default();
        let lines: Vec<(u128, String)> = text
            .lines()
            .map(|line| {
                let (ns, said) = line.split_once(' ').expect("a time, then the command");
                (ns.parse().expect("nanoseconds"), said.to_string())
            })
            .collect();
        if lines.len() >= count {
            return lines;
        }
        assert!(Instant::now() < deadline, "the log has {} of {count} lines: {text}", lines.len());
        std::thread::yield_now();
    }
}

fn now_ns(clock: &MonotonicClock) -> u128 {
    clock.ns(Instant::now())
}

/// Writes `bytes` to the emulator's port, returns the clock before the write.
fn write_to(port: &str, bytes: &[u8], clock: &MonotonicClock) -> (Box<dyn serialport::SerialPort>, u128) {
    let mut link = serialport::new(port, 115_200).timeout(Duration::from_secs(5)).open().unwrap();
    let before = now_ns(clock);
    link.write_all(bytes).unwrap();
    link.flush().unwrap();
    (link, before)
}

#[test]
fn every_family_logs_what_it_takes_in_on_the_system_clock() {
    let clock = MonotonicClock::now();
    let dir = tempfile::tempdir().unwrap();
    let servo_request = Message::QueryMemorySizeRequest.encode().unwrap();
    let rflex_request = RflexCommand::SystemStatus.to_frame().to_bytes().unwrap();
    let families: [(&str, Vec<u8>, usize, &str); 3] = [
        ("servo", [servo_request.clone(), servo_request].concat(), 2, "QueryMemorySizeRequest"),
        ("plen2", b"$HP<VI".to_vec(), 2, "$HP"),
        ("rflex", rflex_request, 1, "SystemStatus"),
    ];
    for (family, bytes, count, said) in families {
        let log = dir.path().join(format!("{family}.log"));
        let sim = common::sim(&["--protocol", family, "--log", log.to_str().unwrap()]);
        let (_link, before) = write_to(&sim.port, &bytes, &clock);
        let logged = lines(&log, count);
        let after = now_ns(&clock);
        assert!(logged[0].1.contains(said), "{family}: {logged:?}");
        assert_eq!(logged.len(), count, "{family}: a line a command, nothing else: {logged:?}");
        for (ns, line) in &logged {
            assert!((before..=after).contains(ns), "{family}: {line:?} at {ns} ns, written at {before}..{after}");
        }
        assert!(logged.windows(2).all(|pair| pair[0].0 <= pair[1].0), "{family}: in time order");
    }
}
