//! What a PLEN2 does with the project's motions, cycle by cycle: the
//! firmware's motion controller (`protocol::plen2::playback`, plen2.md §6)
//! run over the motions as the robot would store them. The editor's preview
//! and `servo-studio trajectory` show this, not an idealised curve.

use std::collections::BTreeMap;

use crate::project::plen2::Plen2Project;
pub use crate::protocol::plen2::DEVICE_IDS;
pub use crate::protocol::plen2::playback::{
    CYCLE_US, LOOP_FOREVER, MotionStore, Player, Start, cycles_for, joint_output, play_out,
};
use crate::protocol::plen2::{Command, FACTORY_LIMIT_TENTHS_DEG, Joint, MotionFrame, MotionHeader};

use super::convert::motion_commands;

/// The project's motions as the robot stores them (`>MH` + `>MF`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StoredMotions {
    slots: BTreeMap<u8, (MotionHeader, Vec<MotionFrame>)>,
}

impl StoredMotions {
    /// Every motion of `project`, in its slot.
    pub fn new(project: &Plen2Project) -> Self {
        let mut slots = BTreeMap::new();
        for motion in &project.motions {
            let mut header = None;
            let mut frames = Vec::new();
            for command in motion_commands(motion) {
                match command {
                    Command::Header(stored) => header = Some(stored),
                    Command::Frame(frame) => frames.push(*frame),
                    _ => {}
                }
            }
            if let Some(header) = header {
                slots.insert(motion.slot, (header, frames));
            }
        }
        Self { slots }
    }
}

impl MotionStore for StoredMotions {
    fn header(&self, slot: u8) -> Option<MotionHeader> {
        let (header, _) = self.slots.get(&slot)?;
        // The firmware drops a header whose frame count is not 1..=20.
        (1..=20).contains(&header.frame_count).then(|| header.clone())
    }

    fn frame(&self, slot: u8, index: u8) -> Option<MotionFrame> {
        let (_, frames) = self.slots.get(&slot)?;
        frames.get(usize::from(index)).cloned()
    }
}

/// A joint's stored settings: home, min, max (tenths of a degree), by device id.
pub type Settings = [(i16, i16, i16); DEVICE_IDS];

/// The joint settings the robot holds: the project's, or the factory's where
/// the project holds none.
pub fn joint_settings(project: &Plen2Project) -> Settings {
    let mut settings = [(0, -FACTORY_LIMIT_TENTHS_DEG, FACTORY_LIMIT_TENTHS_DEG); DEVICE_IDS];
    for joint in Joint::ALL {
        let device = usize::from(joint.device_id());
        settings[device].0 = joint.factory_home_tenths_deg();
        if let Some(setting) = project.joints.iter().find(|setting| setting.joint == joint) {
            settings[device] = (setting.home_tenths_deg, setting.min_tenths_deg, setting.max_tenths_deg);
        }
    }
    settings
}

/// Each joint's value relative to home once clamped to its settings: what the
/// robot's servo really does for a frame value.
pub fn clamped(values: &[i16; DEVICE_IDS], settings: &Settings) -> [i16; DEVICE_IDS] {
    std::array::from_fn(|device| {
        let (home, min, max) = settings[device];
        joint_output(home, min, max, values[device]) - home
    })
}

/// A motion played out: every cycle's frame values (relative to home, before
/// clamping), by device id.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Playback {
    /// What *current* held at `$PM`: where cycle 0 steps from.
    pub from: [i16; DEVICE_IDS],
    /// Cycle k's values, for k from 0.
    pub cycles: Vec<[i16; DEVICE_IDS]>,
    /// The frame approached in each cycle: (slot, frame index).
    pub frames: Vec<(u8, u8)>,
    /// Whether playback ended by itself (else it was cut at the cycles asked for).
    pub ended: bool,
}

impl Playback {
    /// Seconds a cycle takes.
    pub const CYCLE_MS: f64 = CYCLE_US as f64 / 1000.0;

    /// The cycle running at `time_ms` after `$PM` (the last one past the end).
    pub fn cycle_at(&self, time_ms: f64) -> Option<usize> {
        if self.cycles.is_empty() {
            return None;
        }
        // Cycle counts are small and non-negative.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let cycle = (time_ms.max(0.0) / Self::CYCLE_MS).floor() as usize;
        Some(cycle.min(self.cycles.len() - 1))
    }

    /// How long it plays, ms.
    pub fn duration_ms(&self) -> f64 {
        // Cycle counts stay far below 2^52.
        #[allow(clippy::cast_precision_loss)]
        let cycles = self.cycles.len() as f64;
        cycles * Self::CYCLE_MS
    }

    /// The first cycle approaching frame `index` of `slot`, if it plays.
    pub fn first_cycle_of(&self, slot: u8, index: u8) -> Option<usize> {
        self.frames.iter().position(|&frame| frame == (slot, index))
    }
}

/// What *current* holds after `slot` has played from power-up: its last
/// frame reached (for a motion that never ends, its last frame's values).
pub fn after(stored: &StoredMotions, slot: u8, max_cycles: usize) -> [i16; DEVICE_IDS] {
    let mut player = Player::new();
    let played = play_out(&mut player, stored, slot, Start::Play, max_cycles);
    if player.playing().is_none() || played.is_empty() {
        return *player.current();
    }
    let last = stored.header(slot).map_or(0, |header| header.frame_count.saturating_sub(1));
    stored.frame(slot, last).map_or(*player.current(), |frame| frame.values)
}

/// `slot` played with `$PM` from *current* = `from` (all zeros after
/// power-up), for at most `max_cycles` cycles.
pub fn play(stored: &StoredMotions, slot: u8, from: [i16; DEVICE_IDS], max_cycles: usize) -> Playback {
    let mut player = Player::from_frame(from);
    let mut playback = Playback { from, cycles: Vec::new(), frames: Vec::new(), ended: false };
    if !player.start(stored, slot, Start::Play) {
        playback.ended = true;
        return playback;
    }
    while playback.cycles.len() < max_cycles {
        let Some(approaching) = player.approaching() else { break };
        match player.cycle(stored) {
            Some(values) => {
                playback.cycles.push(values);
                playback.frames.push(approaching);
            }
            None => break,
        }
    }
    playback.ended = player.playing().is_none();
    playback
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::plen2::{Frame, LoopRange, Motion, Pose};

    fn motion(slot: u8, frames: &[(u16, i16)]) -> Motion {
        Motion {
            slot,
            name: format!("m{slot}"),
            frames: frames
                .iter()
                .map(|&(transition_ms, value)| {
                    let mut pose = Pose::default();
                    pose.set(Joint::LeftKneePitch, value);
                    Frame::new(transition_ms, pose)
                })
                .collect(),
            loop_range: None,
            jump_slot: None,
        }
    }

    #[test]
    fn a_project_motion_plays_as_stored_with_its_loop_and_jump() {
        let knee = usize::from(Joint::LeftKneePitch.device_id());
        let mut first = motion(3, &[(100, 300), (64, 100)]);
        first.loop_range = Some(LoopRange { begin_frame: 0, end_frame: 1, count: 1 });
        first.jump_slot = Some(4);
        let project = Plen2Project { motions: vec![first, motion(4, &[(32, -50)])], ..Plen2Project::default() };
        let stored = StoredMotions::new(&project);
        let playback = play(&stored, 3, [0; DEVICE_IDS], 1000);
        let knee_values: Vec<i16> = playback.cycles.iter().map(|values| values[knee]).collect();
        // 0 → 300 in 3 cycles (exact steps of 100), → 100 in 2, then the loop once more.
        assert_eq!(&knee_values[..5], &[100, 200, 300, 200, 100]);
        assert_eq!(playback.frames[..5], [(3, 0), (3, 0), (3, 0), (3, 1), (3, 1)]);
        // The second pass starts from exactly 100: steps of (200 << 16) / 3, floored; then the jump.
        assert_eq!(&knee_values[5..10], &[166, 233, 299, 200, 100]);
        assert_eq!(knee_values[10..], [-50], "then slot 4");
        assert!(playback.ended);
        assert_eq!(playback.cycle_at(0.0), Some(0));
        assert_eq!(playback.cycle_at(33.0), Some(1));
        assert_eq!(playback.cycle_at(1e9), Some(10));
        assert_eq!(playback.first_cycle_of(4, 0), Some(10));
        // What a motion played after slot 4 starts from.
        assert_eq!(after(&stored, 4, 1000)[knee], -50);
    }
}
