//! PLEN2 upload figures, over a pseudo-terminal against the emulated robot at
//! its modelled firmware speed: upload + verify of a 20-frame motion, beside
//! the official tool's pacing (32 bytes, then 50 ms; no verification) for the
//! same bytes, and beside the floor (the bytes' wire time plus the EEPROM
//! writes plus the read-back's wire time).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::print_stdout, clippy::cast_precision_loss)]

use std::time::{Duration, Instant};

use servo_studio::device::Cancel;
use servo_studio::device::plen2::{
    Plen2Handle, Plen2ImportOptions, Plen2Options, SlotResult, import, motion_commands, read_slot,
};
use servo_studio::link::{PortName, no_waker};
use servo_studio::project::Family;
use servo_studio::project::plen2::{Frame, Joint, Motion, Plen2Project, Pose};
use servo_studio::sim::{Plen2Sim, Plen2SimCommand, Plen2Timing, spawn_pty};

fn motion(slot: u8) -> Motion {
    let frames = (0..20)
        .map(|i: i16| {
            let mut pose = Pose::default();
            for (j, joint) in (0i16..).zip(Joint::ALL) {
                pose.set(joint, (i * 53 + j * 29) % 600 - 300);
            }
            Frame { transition_ms: 100 + 20 * u16::try_from(i).unwrap(), values_tenths_deg: pose }
        })
        .collect();
    Motion { slot, name: "Bench Walk".into(), frames, loop_range: None, jump_slot: None }
}

fn main() {
    let timing = Plen2Timing::default();
    let robot = spawn_pty(Plen2Sim::new(timing.clone()), no_waker()).unwrap();
    let port = PortName::parse(&robot.port_name).unwrap();
    let settings = servo_studio::device::line_settings(Family::Plen2);
    let handle =
        Plen2Handle::over(servo_studio::link::open(&port, &settings).unwrap(), Plen2Options::default(), no_waker())
            .unwrap();
    let requester = handle.requester();
    let options = Plen2ImportOptions { backup_dir: None, verify: true, force: false };

    let motion_bytes: usize = motion_commands(&motion(0)).iter().map(|c| c.to_ascii().len()).sum();
    let reply_bytes = {
        // The read-back's size, measured once.
        let project = Plen2Project { motions: vec![motion(89)], ..Plen2Project::default() };
        import(&requester, &project, &options, &mut |_| {}, &Cancel::never()).unwrap();
        let reply = requester.get(servo_studio::protocol::plen2::Command::GetMotion { slot: 89 }).unwrap();
        assert!(read_slot(&requester, 89).unwrap().is_some());
        reply.len()
    };

    let mut times = Vec::new();
    let mut rewrites = 0;
    for round in 0..10u8 {
        let project = Plen2Project { motions: vec![motion(round)], ..Plen2Project::default() };
        let began = Instant::now();
        let report = import(&requester, &project, &options, &mut |_| {}, &Cancel::never()).unwrap();
        times.push(began.elapsed());
        assert!(report.slots.iter().all(|(_, r)| *r == SlotResult::Verified), "{report:?}");
        rewrites += report.rewritten;
    }
    let (reply, state) = crossbeam_channel::bounded(1);
    robot.command(Plen2SimCommand::Inspect(reply));
    let state = state.recv_timeout(Duration::from_secs(5)).unwrap();
    times.sort();
    let median = times[times.len() / 2];

    let bytes = u32::try_from(motion_bytes).unwrap();
    let official = Duration::from_millis(50) * bytes.div_ceil(32);
    let wire = timing.line_byte * bytes + timing.reply_byte * u32::try_from(reply_bytes).unwrap();
    let eeprom = timing.header_write + timing.frame_write * 20;
    let floor = wire + eeprom;
    println!("20-frame motion, {motion_bytes} bytes written + {reply_bytes} read back, over {}:", robot.port_name);
    println!(
        "  upload + verify: median {:.1} ms (best {:.1}, worst {:.1} of 10); bytes lost by the robot: {}; \
         commands it dropped: {}; slots written again: {rewrites}",
        median.as_secs_f64() * 1e3,
        times[0].as_secs_f64() * 1e3,
        times[times.len() - 1].as_secs_f64() * 1e3,
        state.lost_bytes,
        state.dropped
    );
    println!(
        "  official pacing (32 bytes, then 50 ms; no verification): {:.0} ms → {:.1}× faster",
        official.as_secs_f64() * 1e3,
        official.as_secs_f64() / median.as_secs_f64()
    );
    println!(
        "  floor (wire {:.1} ms + EEPROM {:.1} ms): {:.1} ms → {:.2}× the floor",
        wire.as_secs_f64() * 1e3,
        eeprom.as_secs_f64() * 1e3,
        floor.as_secs_f64() * 1e3,
        median.as_secs_f64() / floor.as_secs_f64()
    );
}
