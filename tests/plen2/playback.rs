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
        Frame::new(100, pose(&[(knee, 333), (Joint::RightShoulderRoll, -77)])),
        Frame::new(250, pose(&[(knee, -123), (Joint::LeftFootRoll, 45)])),
        Frame::new(8191, pose(&[(knee, 900)])),
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
        frames: vec![Frame::new(64, pose(&[(knee, -400)]))],
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
    let Some(folder) = crate::common::shared("plen2/motions") else { return };
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

fn eased_pose(knee: i16, shoulder: i16) -> Pose {
    let mut pose = Pose::default();
    pose.set(Joint::LeftKneePitch, knee);
    pose.set(Joint::RightShoulderRoll, shoulder);
    pose
}

/// Every curve, authored on the middle frame, is what the robot plays within
/// 1° at every cycle: the project's motion goes through the same path as an
/// upload (baked into straight frames), then the firmware's playback model.
#[test]
fn each_easing_curve_baked_is_played_within_a_degree_at_every_cycle() {
    use servo_studio::project::Easing;
    for easing in Easing::ALL {
        let mut eased = Frame::new(1600, eased_pose(-700, 450));
        eased.easing = easing;
        let authored = Motion {
            slot: 3,
            name: "eased".into(),
            frames: vec![Frame::new(320, eased_pose(200, 0)), eased, Frame::new(96, eased_pose(0, 0))],
            loop_range: None,
            jump_slot: None,
        };
        let project = Plen2Project { motions: vec![authored.clone()], ..Plen2Project::default() };
        let stored = servo_studio::device::plen2::stored_motion(&authored);
        assert!(stored.frames.iter().all(|frame| frame.easing == Easing::Linear));
        let pieces = stored.frames.len() - 2;
        match easing {
            Easing::Linear => assert_eq!(stored, authored),
            Easing::Hold => assert_eq!(pieces, 2, "held, then one cycle to the end"),
            _ => assert!((2..=12).contains(&pieces), "{easing:?}: {pieces} pieces"),
        }
        // The curve, cycle by cycle: 10 cycles of the line, 50 of the curve, 3 of the line.
        let mut wanted: Vec<(f64, f64)> = (1..=10).map(|k| (20.0 * f64::from(k), 0.0)).collect();
        for k in 1..=50 {
            let along = easing.at(f64::from(k) / 50.0);
            wanted.push((200.0 - 900.0 * along, 450.0 * along));
        }
        wanted.extend((1..=3).map(|k| (-700.0 + 700.0 * f64::from(k) / 3.0, 450.0 - 450.0 * f64::from(k) / 3.0)));
        let played = playback::play(&StoredMotions::new(&project), 3, [0; DEVICE_IDS], 10_000).cycles;
        assert_eq!(played.len(), wanted.len(), "{easing:?}: the baked frames take the authored cycles");
        let (knee, shoulder) =
            (usize::from(Joint::LeftKneePitch.device_id()), usize::from(Joint::RightShoulderRoll.device_id()));
        for (cycle, (values, (want_knee, want_shoulder))) in played.iter().zip(&wanted).enumerate() {
            // A straight frame itself rounds by up to a tenth (plen2.md §6); the curve is held to 1°.
            let allowed = if (10..60).contains(&cycle) { 10.0 } else { 1.0 };
            assert!(
                (f64::from(values[knee]) - want_knee).abs() <= allowed,
                "{easing:?} cycle {cycle}: knee {} for {want_knee}",
                values[knee]
            );
            assert!((f64::from(values[shoulder]) - want_shoulder).abs() <= allowed, "{easing:?} cycle {cycle}");
        }
        // And the emulated robot, given the upload's commands, outputs the same cycles.
        assert_eq!(emulated(&project, 3, wanted.len()), modelled(&project, 3, wanted.len()), "{easing:?}");
    }
}
