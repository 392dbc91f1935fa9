//! The I/O thread spaces writes by the connection's minimum gap (an rFLEX base
//! ignores commands sent too rapidly), and sends at once without one.

#![allow(clippy::unwrap_used)]

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use servo_studio::link::{Connection, Driver, no_waker, spawn};

/// Sends each command's bytes as its own write.
struct Burst {
    queue: VecDeque<Vec<u8>>,
}

impl Driver for Burst {
    type Command = Vec<Vec<u8>>;
    type Event = ();

    fn handle_command(&mut self, _now: Instant, command: Vec<Vec<u8>>) {
        self.queue.extend(command);
    }
    fn handle_input(&mut self, _now: Instant, _bytes: &[u8]) {}
    fn handle_timeout(&mut self, _now: Instant) {}
    fn handle_disconnect(&mut self, _reason: &str) {}
    fn poll_transmit(&mut self, _now: Instant) -> Option<Vec<u8>> {
        self.queue.pop_front()
    }
    fn poll_event(&mut self) -> Option<()> {
        None
    }
    fn poll_timeout(&self) -> Option<Instant> {
        None
    }
}

/// Sends four one-byte writes; returns when they were asked for and when each
/// arrived at the other end.
fn arrivals(gap: Duration) -> (Instant, Vec<Instant>) {
    let (ours, mut theirs) = Connection::memory_pair();
    let link = spawn(ours.with_min_write_gap(gap), Burst { queue: VecDeque::new() }, no_waker()).unwrap();
    let asked = Instant::now();
    link.commands().send(vec![vec![1], vec![2], vec![3], vec![4]]).unwrap();
    let mut times = Vec::new();
    let mut byte = [0u8; 1];
    while times.len() < 4 {
        assert_eq!(theirs.reader_mut().read(&mut byte).unwrap(), 1);
        assert_eq!(usize::from(byte[0]), times.len() + 1, "in order");
        times.push(Instant::now());
    }
    (asked, times)
}

#[test]
fn writes_are_spaced_by_the_minimum_gap() {
    let gap = Duration::from_millis(15);
    let (asked, times) = arrivals(gap);
    // The first write goes after the command was sent, each next one a gap
    // later at the earliest; the reader can only see them later still.
    assert!(times[3] - asked >= 3 * gap, "{:?}", times[3] - asked);
}
