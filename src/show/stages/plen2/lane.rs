//! A PLEN2 on the show's timeline: before its first cue its joints are at
//! home; from a cue on, where the firmware's playback of the motion in the
//! cue's slot has them, cycle by cycle (plen2.md §6), played from home once
//! and on further only as far as it is asked (a motion that loops forever is
//! followed for ten minutes at most for its length).

use std::collections::HashMap;

use crate::device::plen2::playback::{self, DEVICE_IDS, Playback, StoredMotions};
use crate::project::{Family, Project};
use crate::show::at::Posed;
use crate::show::timeline::{FamilyTimeline, Lane, latest, whole_ms};
use crate::show::{Device, Start};

/// The longest a motion is played for its length, ms (a motion that loops forever: ten minutes).
const LONGEST_MOTION_MS: f64 = 600_000.0;

inventory::submit! {
    FamilyTimeline { family: Family::Plen2, lane: || Box::<Plen2Lane>::default() }
}

/// A motion's playback as far as it was asked for.
#[derive(Debug)]
struct Played {
    playback: Playback,
    asked: usize,
}

/// One PLEN2's motions, played as they are asked for.
#[derive(Debug, Default)]
struct Plen2Lane {
    plays: HashMap<u8, Played>,
}

/// The motion in `slot` of `project` played from home, at most `cycles` long.
fn motion_playback(project: &Project, slot: u8, cycles: usize) -> Playback {
    let stored = StoredMotions::new(&project.plen2);
    playback::play(&stored, slot, [0; DEVICE_IDS], cycles)
}

/// The most cycles a cue's motion is followed for its length.
fn longest_motion_cycles() -> usize {
    // Cycle counts from a bounded time.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let cycles = (LONGEST_MOTION_MS / Playback::CYCLE_MS) as usize;
    cycles
}

impl Plen2Lane {
    /// The motion's playback, at least `cycles` long unless it ended by itself.
    fn playback(&mut self, project: &Project, slot: u8, cycles: usize) -> &Playback {
        let played = self
            .plays
            .entry(slot)
            .or_insert_with(|| Played { playback: motion_playback(project, slot, cycles), asked: cycles });
        if played.asked < cycles && !played.playback.ended {
            // Asked past what was played: twice as far (a scrub moving on costs a replay now and then).
            let asked = cycles.max(played.asked * 2);
            *played = Played { playback: motion_playback(project, slot, asked), asked };
        }
        &played.playback
    }

    /// The joints `since_ms` after the motion in `slot` started (held at its end).
    fn joints_at(&mut self, project: &Project, slot: u8, since_ms: u64) -> [i16; DEVICE_IDS] {
        // Whole ms and cycle counts of at most an hour.
        #[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let done = (since_ms as f64 / Playback::CYCLE_MS) as usize;
        if done == 0 {
            return [0; DEVICE_IDS];
        }
        let played = self.playback(project, slot, done);
        // After `done` whole cycles, `done` steps were output (cycles[k] is step k + 1's).
        played.cycles.get(done - 1).or(played.cycles.last()).copied().unwrap_or(played.from)
    }
}

impl Lane for Plen2Lane {
    fn length_ms(&mut self, project: &Project, start: &Start) -> u64 {
        let Start::Slot(slot) = *start else { return 0 };
        whole_ms(self.playback(project, slot, longest_motion_cycles()).duration_ms())
    }

    fn posed_at(&mut self, device: &Device, cues: &[(u64, Start)], t_ms: u64) -> Posed {
        let mut values = [0; DEVICE_IDS];
        if let Some((at_ms, Start::Slot(slot))) = latest(cues, t_ms) {
            values = self.joints_at(&device.project, slot, t_ms - at_ms);
        }
        Posed::Joints(values)
    }
}
