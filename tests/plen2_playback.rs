//! The PLEN2 playback model (plen2.md §6) against the emulated robot playing
//! the same motions, cycle for cycle: motions are written to the emulator as
//! `>MH`/`>MF` commands, started with `$PM`, and every cycle's joint outputs
//! are compared with the model's (home + value, clamped), in virtual time.
//! The official motions are read from `../shared/plen2/motions` (skipped with
//! a notice when absent).

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Instant;

use servo_studio::device::plen2::playback::{self, StoredMotions, joint_settings};
use servo_studio::link::Driver;
use servo_studio::project::plen2::{Frame, JointSetting, LoopRange, Motion, Plen2Project, Pose};
use servo_studio::protocol::plen2::{Command, DEVICE_IDS, Joint};
use servo_studio::sim::{Plen2Sim, Plen2SimEvent, Plen2Timing};

/// The emulator's joint outputs for `cycles` cycles after `$PM slot`.
fn emulated(project: &Plen2Project, slot: u8, cycles: usize) -> Vec<[i16; DEVICE_IDS]> {
    let mut sim = Plen2Sim::new(Plen2Timing::default());
    sim.preload(&servo_studio::device::plen2::store_commands(project));
    let mut now = Instant::now();
    sim.handle_input(now, Command::PlayMotion { slot }.to_ascii().as_bytes());
    let mut outputs = Vec::new();
    // Virtual time: the emulator is told the time of its next deadline, never slept for.
    while outputs.len() < cycles {
        let Some(at) = sim.poll_timeout() else { break };
        now = now.max(at);
        sim.handle_timeout(now);
        while let Some(event) = sim.poll_event() {
            if let Plen2SimEvent::Cycle(angles) = event {
                outputs.push(angles);
            }
        }
    }
    outputs.truncate(cycles);
    outputs
}

/// The model's joint outputs for the same: home + value, clamped.
fn modelled(project: &Plen2Project, slot: u8, cycles: usize) -> Vec<[i16; DEVICE_IDS]> {
    let stored = StoredMotions::new(project);
    let settings = joint_settings(project);
    let played = playback::play(&stored, slot, [0; DEVICE_IDS], cycles);
    played
        .cycles
        .iter()
        .map(|values| {
            std::array::from_fn(|device| {
                let (home, min, max) = settings[device];
                playback::joint_output(home, min, max, values[device])
            })
        })
        .collect()
}

fn assert_same(project: &Plen2Project, slot: u8, cycles: usize, what: &str) -> usize {
    let model = modelled(project, slot, cycles);
    let robot = emulated(project, slot, model.len().max(1) + 5);
    assert!(!model.is_empty(), "{what}: the model plays nothing");
    for (cycle, (m, r)) in model.iter().zip(&robot).enumerate() {
        assert_eq!(m, r, "{what}: cycle {cycle} differs");
    }
    if model.len() < cycles {
        // It ended: so did the robot, at the same cycle.
        assert_eq!(
            robot.len(),
            model.len(),
            "{what}: the robot played {} cycles, the model {}",
            robot.len(),
            model.len()
        );
    } else {
        assert!(robot.len() >= model.len(), "{what}: the robot stopped after {} cycles", robot.len());
    }
    model.len()
}

fn pose(values: &[(Joint, i16)]) -> Pose {
    let mut pose = Pose::default();
    for &(joint, value) in values {
        pose.set(joint, value);
    }
    pose
}

#[test]
fn a_looping_jumping_clamped_motion_plays_on_the_emulator_as_the_model_says() {
    let knee = Joint::LeftKneePitch;
    let frames = vec![
        Frame { transition_ms: 100, values_tenths_deg: pose(&[(knee, 333), (Joint::RightShoulderRoll, -77)]) },
        Frame { transition_ms: 250, values_tenths_deg: pose(&[(knee, -123), (Joint::LeftFootRoll, 45)]) },
        Frame { transition_ms: 8191, values_tenths_deg: pose(&[(knee, 900)]) },
    ];
    let first = Motion {
        slot: 7,
        name: "Test".into(),
        frames,
        loop_range: Some(LoopRange { begin_frame: 0, end_frame: 1, count: 2 }),
        jump_slot: Some(8),
    };
    let second = Motion {
        slot: 8,
        name: "After".into(),
        frames: vec![Frame { transition_ms: 64, values_tenths_deg: pose(&[(knee, -400)]) }],
        loop_range: None,
        jump_slot: None,
    };
    // A calibrated robot: the knee's home moved, its range narrowed (so values clamp).
    let joints = vec![JointSetting { joint: knee, min_tenths_deg: -300, max_tenths_deg: 700, home_tenths_deg: 450 }];
    let project = Plen2Project { joints, motions: vec![first, second], play_lists: Vec::new() };
    let played = assert_same(&project, 7, 10_000, "loop, jump, clamp");
    // 3 passes of (3 + 7 cycles), then 255, then slot 8's 2.
    assert_eq!(played, 3 * (3 + 7) + 255 + 2);
}

#[test]
fn the_official_motions_play_on_the_emulator_as_the_model_says() {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/plen2/motions");
    if !folder.is_dir() {
        eprintln!("skipped: {} is absent", folder.display());
        return;
    }
    let motions = servo_studio::project::motion_json::load_motions(&folder).unwrap();
    assert_eq!(motions.len(), 90);
    let project = Plen2Project { motions, ..Plen2Project::default() };
    let mut looping = 0;
    for motion in &project.motions {
        // 30 s of each (the walks loop forever).
        let played = assert_same(&project, motion.slot, 916, &format!("slot {} {}", motion.slot, motion.name));
        if played == 916 {
            looping += 1;
        }
    }
    assert!(looping >= 10, "the walks loop forever: {looping}");
}
