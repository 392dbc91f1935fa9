//! The paced driver against the emulated firmware in virtual time: no threads,
//! no scheduler, so what is measured is the pacing alone. Every byte the
//! driver hands out reaches the emulator at that instant; whatever the driver
//! sends, the emulator's 64-byte ring must never overflow.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::{Duration, Instant};

use servo_studio::device::plen2::{Plen2Command, Plen2Driver, Plen2Options, motion_commands};
use servo_studio::link::Driver;
use servo_studio::project::plen2::{Frame, Joint, Motion, Pose};
use servo_studio::sim::{Plen2Sim, Plen2Timing};

fn motion(slot: u8) -> Motion {
    let frames = (0..20)
        .map(|i: i16| {
            let mut pose = Pose::default();
            for (index, joint) in Joint::ALL.into_iter().enumerate() {
                pose.set(joint, (i * 37 + i16::try_from(index).unwrap() * 11) % 700 - 350);
            }
            Frame { transition_ms: 100, values_tenths_deg: pose }
        })
        .collect();
    Motion { slot, name: format!("Motion {slot}"), frames, loop_range: None, jump_slot: None }
}

/// Runs driver and emulator together until the emulator has executed
/// `expected` commands; returns that instant and the driver's largest write.
fn run(driver: &mut Plen2Driver, sim: &mut Plen2Sim, start: Instant, expected: u64) -> (Instant, usize) {
    let mut now = start;
    let mut largest = 0;
    let limit = start + Duration::from_secs(60);
    loop {
        while let Some(bytes) = driver.poll_transmit(now) {
            largest = largest.max(bytes.len());
            sim.handle_input(now, &bytes);
        }
        while let Some(reply) = sim.poll_transmit(now) {
            driver.handle_input(now, &reply);
        }
        if sim.state().executed >= expected {
            return (now, largest);
        }
        let next = [driver.poll_timeout(), sim.poll_timeout()].into_iter().flatten().map(|t| t.max(now)).min();
        now = next.unwrap_or_else(|| panic!("stalled: {:?}", sim.state()));
        assert!(now < limit, "never finished: {:?}", sim.state());
        driver.handle_timeout(now);
        sim.handle_timeout(now);
    }
}

#[test]
fn a_paced_upload_never_overflows_the_ring_in_virtual_time() {
    let mut driver = Plen2Driver::new(Plen2Options::default());
    let mut sim = Plen2Sim::new(Plen2Timing::default());
    let start = Instant::now();
    let mut sent = 0;
    for slot in [0, 1, 2] {
        for command in motion_commands(&motion(slot)) {
            sent += 1;
            driver.handle_command(start, Plen2Command::Send { command, done: None });
        }
    }
    // Live moves interleaved, as a user dragging a slider during an upload would.
    driver.handle_command(start, Plen2Command::LiveAngles(vec![(0, 100), (12, -100)]));
    let (end, largest) = run(&mut driver, &mut sim, start, sent + 2);
    let state = sim.state();
    assert_eq!(state.lost_bytes, 0, "the ring never overflowed");
    assert_eq!(state.dropped, 0);
    assert_eq!(state.written_slots, [0, 1, 2]);
    assert!(largest <= 64, "no write larger than the ring: {largest}");
    // And not by crawling: 3 × (21 frames' bytes and EEPROM writes) within 1.3× of the floor.
    let bytes: u32 =
        (0..3).flat_map(|s| motion_commands(&motion(s))).map(|c| u32::try_from(c.to_ascii().len()).unwrap()).sum();
    let timing = Plen2Timing::default();
    let floor = timing.byte_read * bytes + (timing.header_write + timing.frame_write * 20) * 3;
    assert!(end - start < floor * 13 / 10, "{:?} against a floor of {floor:?}", end - start);
}
