//! What the firmware outputs when it plays a stored motion, cycle by cycle
//! (plen2.md §6, firmware 1.4.2's MotionController): two frame buffers,
//! *current* and *next*; `(transition / 32) & 0xFF` cycles of 32.768 ms per
//! frame; linear steps in 16.16 fixed point from *current*; loops that run
//! their section count + 1 times (a stored 0 wraps to 255: forever); jumps (to
//! a slot ≥ 90: the motion replays forever); a frame of 0 cycles reached from
//! another frame skipped at once. Sans-IO and clock-free: each call of
//! [`Player::cycle`] is one cycle. The emulated robot plays with it; the
//! editor's preview and `servo-studio trajectory` compute what the robot
//! will do with it.

use super::command::{MotionFrame, MotionHeader};
use super::joint::DEVICE_IDS;

/// One cycle of the firmware's PWM (8 timer ticks of 4.096 ms), µs.
pub const CYCLE_US: u64 = 32_768;

/// The loop count that never runs out.
pub const LOOP_FOREVER: u8 = 0xff;

/// Cycles the firmware gives a frame of `transition_ms`: `(ms / 32) & 0xFF`
/// (100 ms → 3, 8191 ms → 255, 8192 ms → 0: the 8-bit counter wraps).
pub fn cycles_for(transition_ms: u16) -> u8 {
    // The mask is the point: the firmware keeps the count in 8 bits.
    #[allow(clippy::cast_possible_truncation)]
    let cycles = ((transition_ms / 32) & 0xff) as u8;
    cycles
}

/// The step per cycle toward a frame, 16.16: `((to << 16) − (from << 16)) /
/// cycles` in 32 bits, truncating toward zero as C does (0 for 0 cycles: the
/// robot divides by zero there). `from_fp` and `to_fp` are already shifted.
fn step_fp(from_fp: i32, to_fp: i32, cycles: u8) -> i32 {
    if cycles == 0 { 0 } else { to_fp.wrapping_sub(from_fp) / i32::from(cycles) }
}

/// The value a joint is given at cycle `k` (1..=`cycles`) of a move from the
/// frame value `from` to `to` over `cycles` cycles (before clamping): the
/// firmware's 16.16 arithmetic, exactly as [`Player::cycle`] runs it. At `k =
/// cycles` it can be one below `to` (truncated steps, floored output).
pub fn step_value(from: i16, to: i16, cycles: u8, k: u16) -> i16 {
    let from_fp = i32::from(from) << 16;
    let diff_fp = step_fp(from_fp, i32::from(to) << 16, cycles);
    let now_fp = from_fp.wrapping_add(diff_fp.wrapping_mul(i32::from(k)));
    i16::try_from(now_fp >> 16).unwrap_or(0)
}

/// What a joint is set to for a frame value: home + value, clamped to [min, max].
pub fn joint_output(home: i16, min: i16, max: i16, value: i16) -> i16 {
    let angle = i32::from(home) + i32::from(value);
    // Clamped to an i16 range first: min ≤ max is not guaranteed by a file.
    let angle = angle.clamp(i32::from(min.min(max)), i32::from(max.max(min)));
    i16::try_from(angle).unwrap_or(home)
}

/// The motions the player reads: a robot's EEPROM, or a project's slots.
pub trait MotionStore {
    /// The header stored in `slot`, if it holds one.
    fn header(&self, slot: u8) -> Option<MotionHeader>;
    /// Frame `index` of `slot`, if stored.
    fn frame(&self, slot: u8, index: u8) -> Option<MotionFrame>;
}

/// How a motion is started.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Start {
    /// `$PM`: as stored (its loop and jump).
    Play,
    /// A `#PU` popped from the queue: `plays` ≥ 2 loops the whole motion (or
    /// its own loop section) that many times, 1 disables its loop, 0 loops
    /// forever; its jump is ignored.
    Queued {
        /// How many times.
        plays: u8,
    },
}

/// The frame being approached and the steps toward it.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Approach {
    /// The playing motion's header (its loop count runs down; a jump replaces it).
    header: MotionHeader,
    /// The frame in *next*.
    index: u8,
    /// Its values, relative to home.
    values: [i16; DEVICE_IDS],
    /// Where each joint is, 16.16.
    now_fp: [i32; DEVICE_IDS],
    /// Its step per cycle, 16.16.
    diff_fp: [i32; DEVICE_IDS],
    /// Cycles left before the next frame is loaded (the 8-bit counter, 0 wrapping to 256).
    cycles_left: u16,
}

/// The firmware's motion controller.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Player {
    /// The *current* frame buffer: the last frame reached (all zeros after power-up).
    current: [i16; DEVICE_IDS],
    /// The *next* frame buffer and the steps, while a motion plays.
    approach: Option<Approach>,
}

impl Player {
    /// A player just after power-up: *current* all zeros, nothing playing.
    pub fn new() -> Self {
        Self::default()
    }

    /// A player whose *current* buffer holds `values` (the last frame of the
    /// motion played before).
    pub fn from_frame(values: [i16; DEVICE_IDS]) -> Self {
        Self { current: values, approach: None }
    }

    /// The *current* frame buffer.
    pub fn current(&self) -> &[i16; DEVICE_IDS] {
        &self.current
    }

    /// The slot playing, if any.
    pub fn playing(&self) -> Option<u8> {
        self.approach.as_ref().map(|approach| approach.header.slot)
    }

    /// The frame being approached (slot, index), if playing.
    pub fn approaching(&self) -> Option<(u8, u8)> {
        self.approach.as_ref().map(|approach| (approach.header.slot, approach.index))
    }

    /// Starts `slot` (replacing what plays): frame 0 goes into *next*, the
    /// steps start from *current*. False when the slot holds no motion.
    pub fn start(&mut self, store: &impl MotionStore, slot: u8, start: Start) -> bool {
        let Some(mut header) = store.header(slot) else { return false };
        if let Start::Queued { plays } = start {
            header.jump_on = false;
            match plays {
                1 => header.loop_on = false,
                plays => {
                    if !header.loop_on {
                        header.loop_begin = 0;
                        header.loop_end = header.frame_count.saturating_sub(1);
                    }
                    header.loop_on = true;
                    header.loop_count = if plays == 0 { LOOP_FOREVER } else { plays - 1 };
                }
            }
        }
        self.load(store, header, 0, true);
        true
    }

    /// `$SM`: loop and jump cleared, the motion ends after its last frame.
    pub fn stop_after_last(&mut self) {
        if let Some(approach) = &mut self.approach {
            approach.header.loop_on = false;
            approach.header.jump_on = false;
        }
    }

    /// Stops at once (the buffers keep what they hold).
    pub fn halt(&mut self) {
        self.approach = None;
    }

    /// Loads frame `index` of the header's slot into *next* and works out the
    /// steps from *current*. A frame that is not stored stops playback. A
    /// frame of 0 cycles is held 256 cycles when it is the first of a start
    /// (the robot divides by zero there: undefined, `check` refuses it); reached
    /// from another frame it is skipped at once (see [`Player::cycle`]).
    fn load(&mut self, store: &impl MotionStore, header: MotionHeader, index: u8, first: bool) {
        let Some(frame) = store.frame(header.slot, index) else {
            self.approach = None;
            return;
        };
        let cycles = cycles_for(frame.transition_ms);
        let mut now_fp = [0i32; DEVICE_IDS];
        let mut diff_fp = [0i32; DEVICE_IDS];
        for device in 0..DEVICE_IDS {
            let from = i32::from(self.current[device]) << 16;
            let to = i32::from(frame.values[device]) << 16;
            now_fp[device] = from;
            // Rust's `/` truncates toward zero, as C's does. A count of 0
            // divides by zero on the robot (undefined): held still here.
            diff_fp[device] = step_fp(from, to, cycles);
        }
        let cycles_left = match (cycles, first) {
            (0, true) => 256,
            (cycles, _) => u16::from(cycles),
        };
        self.approach = Some(Approach { header, index, values: frame.values, now_fp, diff_fp, cycles_left });
    }

    /// One cycle: each joint's frame value this cycle (relative to home,
    /// before clamping: the joint is set to [`joint_output`] of it), or `None`
    /// when nothing plays. After the frame's last cycle the next frame is
    /// loaded (or playback stops); frames of 0 cycles it reaches are skipped
    /// in the same cycle — none of their values is output, but each becomes
    /// *current*. A motion that would skip without end (every frame of a loop
    /// forever under 32 ms) outputs nothing more and stops.
    pub fn cycle(&mut self, store: &impl MotionStore) -> Option<[i16; DEVICE_IDS]> {
        let approach = self.approach.as_mut()?;
        let mut out = [0i16; DEVICE_IDS];
        for ((now, diff), value) in approach.now_fp.iter_mut().zip(&approach.diff_fp).zip(&mut out) {
            *now = now.wrapping_add(*diff);
            // `>>` on i32 is arithmetic: it floors.
            *value = i16::try_from(*now >> 16).unwrap_or(0);
        }
        approach.cycles_left -= 1;
        let mut skipped = 0;
        while self.approach.as_ref().is_some_and(|approach| approach.cycles_left == 0) {
            if skipped > MAX_SKIPS {
                self.approach = None;
                break;
            }
            skipped += 1;
            self.advance(store);
        }
        Some(out)
    }

    /// *next* becomes *current*; then the loop, the jump, the next frame, or the end.
    fn advance(&mut self, store: &impl MotionStore) {
        let Some(Approach { mut header, index, values, .. }) = self.approach.take() else { return };
        self.current = values;
        let last = header.frame_count.saturating_sub(1);
        if header.loop_on && index >= header.loop_end {
            // The firmware decrements first (a stored 0 wraps to 255: forever),
            // and a count that reaches 0 switches the loop off for next time.
            if header.loop_count != LOOP_FOREVER {
                header.loop_count = header.loop_count.wrapping_sub(1);
            }
            if header.loop_count == 0 {
                header.loop_on = false;
            }
            let begin = header.loop_begin;
            self.load(store, header, begin, false);
            return;
        }
        if header.jump_on && index >= last {
            let jump = header.jump_slot;
            if jump >= super::SLOTS {
                // No header there to read: this one stays, and the motion replays.
                self.load(store, header, 0, false);
            } else if let Some(jumped) = store.header(jump) {
                self.load(store, jumped, 0, false);
            }
            return;
        }
        if index < last {
            self.load(store, header, index + 1, false);
        }
    }
}

/// Frames of 0 cycles skipped in one cycle before a motion is taken as
/// outputting nothing more (a motion has at most 20 frames; a loop of them
/// forever would spin without end).
const MAX_SKIPS: usize = 64;

/// Every cycle's output of `slot` played from a player in `player`'s state,
/// until it stops or `max_cycles` have run (a loop forever never stops).
pub fn play_out(
    player: &mut Player,
    store: &impl MotionStore,
    slot: u8,
    start: Start,
    max_cycles: usize,
) -> Vec<[i16; DEVICE_IDS]> {
    let mut cycles = Vec::new();
    if !player.start(store, slot, start) {
        return cycles;
    }
    while cycles.len() < max_cycles {
        match player.cycle(store) {
            Some(out) => cycles.push(out),
            None => break,
        }
    }
    cycles
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;

    /// Motions by slot: (header, frames as (transition, value of device 0)).
    #[derive(Default)]
    struct Store(BTreeMap<u8, (MotionHeader, Vec<MotionFrame>)>);

    impl Store {
        fn with(mut self, slot: u8, frames: &[(u16, i16)], change: impl FnOnce(&mut MotionHeader)) -> Self {
            let mut header = MotionHeader {
                slot,
                name: [b' '; 20],
                loop_on: false,
                loop_begin: 0,
                loop_end: 0,
                loop_count: 0,
                jump_on: false,
                jump_slot: 0,
                frame_count: u8::try_from(frames.len()).unwrap_or(0),
            };
            change(&mut header);
            let frames = frames
                .iter()
                .enumerate()
                .map(|(index, &(transition_ms, value))| {
                    let mut values = [0; DEVICE_IDS];
                    values[0] = value;
                    values[12] = -value;
                    MotionFrame { slot, index: u8::try_from(index).unwrap_or(0), transition_ms, values }
                })
                .collect();
            self.0.insert(slot, (header, frames));
            self
        }
    }

    impl MotionStore for Store {
        fn header(&self, slot: u8) -> Option<MotionHeader> {
            self.0.get(&slot).map(|(header, _)| header.clone())
        }
        fn frame(&self, slot: u8, index: u8) -> Option<MotionFrame> {
            self.0.get(&slot).and_then(|(_, frames)| frames.get(usize::from(index)).cloned())
        }
    }

    #[test]
    fn step_value_is_what_the_player_outputs_at_every_cycle() {
        // Frames of every length from 1 to 255 cycles, values up and down,
        // far apart and one tenth apart, including the i16 extremes (wrapping).
        let values: [i16; 9] = [0, 1, -1, 7, -900, 900, 1234, i16::MAX, -i16::MAX];
        for (index, &to) in values.iter().enumerate() {
            let from = values[(index * 5 + 3) % values.len()];
            for cycles in [1u8, 2, 3, 7, 31, 100, 255] {
                let transition_ms = u16::from(cycles) * 32;
                let store = Store::default().with(1, &[(transition_ms, to)], |_| {});
                let mut start = [0; DEVICE_IDS];
                start[0] = from;
                start[12] = from.wrapping_neg();
                let mut player = Player::from_frame(start);
                assert!(player.start(&store, 1, Start::Play));
                for k in 1..=u16::from(cycles) {
                    let out = player.cycle(&store).expect("the frame plays");
                    assert_eq!(out[0], step_value(from, to, cycles, k), "{from} → {to} in {cycles}, cycle {k}");
                    assert_eq!(out[12], step_value(from.wrapping_neg(), to.wrapping_neg(), cycles, k));
                }
                assert_eq!(player.cycle(&store), None, "one frame of {cycles} cycles is {cycles} outputs");
            }
        }
    }

    fn device0(cycles: &[[i16; DEVICE_IDS]]) -> Vec<i16> {
        cycles.iter().map(|out| out[0]).collect()
    }

    #[test]
    fn cycles_per_frame_are_the_transition_over_32_in_8_bits() {
        assert_eq!(cycles_for(100), 3);
        assert_eq!(cycles_for(32), 1);
        assert_eq!(cycles_for(31), 0);
        assert_eq!(cycles_for(8191), 255);
        assert_eq!(cycles_for(8192), 0, "wraps");
        assert_eq!(cycles_for(8224), 1);
    }

    #[test]
    fn steps_are_16_16_fixed_point_truncated_then_floored() {
        // 0 → 100 in 100 ms: 3 cycles, diff = 6553600 / 3 = 2184533.
        // 2184533 >> 16 = 33; 4369066 >> 16 = 66; 6553599 >> 16 = 99 (not 100).
        let store = Store::default().with(0, &[(100, 100)], |_| {});
        let cycles = play_out(&mut Player::new(), &store, 0, Start::Play, 100);
        assert_eq!(device0(&cycles), [33, 66, 99]);
        // Downward the shift floors: −33.33 → −34, −66.67 → −67, −99.99 → −100.
        assert_eq!(cycles.iter().map(|out| out[12]).collect::<Vec<_>>(), [-34, -67, -100]);
    }

    #[test]
    fn the_next_frame_starts_from_the_exact_values_and_a_motion_from_the_last_one_played() {
        // 100 then 0, each 100 ms: the second frame steps from exactly 100.
        let store = Store::default().with(0, &[(100, 100), (100, 0)], |_| {}).with(1, &[(64, 50)], |_| {});
        let mut player = Player::new();
        let cycles = play_out(&mut player, &store, 0, Start::Play, 100);
        // (0 − 6553600) / 3 = −2184533: 100 − 33.33 → 66, 33, 0.
        assert_eq!(device0(&cycles), [33, 66, 99, 66, 33, 0]);
        assert_eq!(player.current()[0], 0);
        // Slot 1 starts from slot 0's last frame (0), 2 cycles to 50.
        let cycles = play_out(&mut player, &store, 1, Start::Play, 100);
        assert_eq!(device0(&cycles), [25, 50]);
        // Played again, it starts from its own last frame: no movement at all.
        let cycles = play_out(&mut player, &store, 1, Start::Play, 100);
        assert_eq!(device0(&cycles), [50, 50]);
    }

    #[test]
    fn a_loop_of_count_c_runs_its_section_c_plus_one_times() {
        // Frames 0..3 (values 10, 20, 30, 40), 32 ms each (1 cycle): loop 1..=2 count 1.
        let frames = [(32, 10), (32, 20), (32, 30), (32, 40)];
        let store = Store::default().with(0, &frames, |header| {
            header.loop_on = true;
            header.loop_begin = 1;
            header.loop_end = 2;
            header.loop_count = 1;
        });
        let cycles = play_out(&mut Player::new(), &store, 0, Start::Play, 100);
        assert_eq!(device0(&cycles), [10, 20, 30, 20, 30, 40]);
        let store = Store::default().with(0, &frames, |header| {
            header.loop_on = true;
            header.loop_begin = 1;
            header.loop_end = 2;
            header.loop_count = 0;
        });
        let cycles = play_out(&mut Player::new(), &store, 0, Start::Play, 9);
        assert_eq!(device0(&cycles), [10, 20, 30, 20, 30, 20, 30, 20, 30], "count 0 wraps to 255: forever");
        let store = Store::default().with(0, &frames, |header| {
            header.loop_on = true;
            header.loop_begin = 1;
            header.loop_end = 2;
            header.loop_count = LOOP_FOREVER;
        });
        let cycles = play_out(&mut Player::new(), &store, 0, Start::Play, 9);
        assert_eq!(device0(&cycles), [10, 20, 30, 20, 30, 20, 30, 20, 30], "255: forever");
    }

    /// plen2.md §6 by hand: frames 100 then 300, 100 ms each (3 cycles),
    /// `"loop", [0, 1, 0]`: the stored 0 wraps to 255 at the first pass's
    /// end, so the section repeats forever and the frame after it (and any
    /// jump) is never reached.
    #[test]
    fn a_loop_of_count_0_runs_forever_with_the_firmwares_figures() {
        let store = Store::default().with(0, &[(100, 100), (100, 300), (100, 0)], |header| {
            header.loop_on = true;
            header.loop_begin = 0;
            header.loop_end = 1;
            header.loop_count = 0;
            header.jump_on = true;
            header.jump_slot = 1;
        });
        let mut player = Player::new();
        let cycles = play_out(&mut player, &store, 0, Start::Play, 12);
        assert_eq!(device0(&cycles), [33, 66, 99, 166, 233, 299, 233, 166, 100, 166, 233, 299]);
        let later = play_out(&mut player, &store, 0, Start::Play, 2000);
        assert_eq!(later.len(), 2000, "still playing after 2000 cycles");
        assert!(later.iter().all(|out| out[0] >= 100), "frame 2 (value 0) is never reached");
        assert_eq!(player.playing(), Some(0));
    }

    /// A jump to a slot ≥ 90 has no header to read: the motion's own header
    /// stays and its frame 0 follows its last, forever.
    #[test]
    fn a_jump_to_a_slot_of_90_or_more_replays_the_motion_forever() {
        let store = Store::default().with(0, &[(64, 100), (32, 50)], |header| {
            header.jump_on = true;
            header.jump_slot = 90;
        });
        let mut player = Player::new();
        let cycles = play_out(&mut player, &store, 0, Start::Play, 9);
        // 0 → 100 in 2 cycles, 50 in 1, then frame 0 again from 50: 75, 100; 50; …
        assert_eq!(device0(&cycles), [50, 100, 50, 75, 100, 50, 75, 100, 50]);
        assert_eq!(player.playing(), Some(0));
        // A jump to an empty slot below 90 ends the motion, as before.
        let store = Store::default().with(0, &[(64, 100)], |header| {
            header.jump_on = true;
            header.jump_slot = 7;
        });
        assert_eq!(device0(&play_out(&mut Player::new(), &store, 0, Start::Play, 100)), [50, 100]);
    }

    /// A frame of 0 cycles reached from another: none of its values is
    /// output, but the next frame steps from them (a visible jump).
    #[test]
    fn a_frame_of_0_cycles_reached_from_another_is_skipped_but_starts_the_next() {
        // 100 in 3 cycles; 300 in 0 ms (skipped); 210 in 3 cycles, from 300.
        let store = Store::default().with(0, &[(100, 100), (0, 300), (100, 210)], |_| {});
        let cycles = play_out(&mut Player::new(), &store, 0, Start::Play, 100);
        assert_eq!(device0(&cycles), [33, 66, 99, 270, 240, 210]);
        // 8192 ms wraps to 0 cycles: skipped the same way.
        let store = Store::default().with(0, &[(100, 90), (8192, 300), (64, 200)], |_| {});
        assert_eq!(device0(&play_out(&mut Player::new(), &store, 0, Start::Play, 100)), [30, 60, 90, 250, 200]);
        // Every frame of a loop forever under 32 ms: nothing more is output, playback stops.
        let store = Store::default().with(0, &[(64, 10), (0, 20), (0, 30)], |header| {
            header.loop_on = true;
            header.loop_begin = 1;
            header.loop_end = 2;
            header.loop_count = LOOP_FOREVER;
        });
        let mut player = Player::new();
        assert_eq!(device0(&play_out(&mut player, &store, 0, Start::Play, 100)), [5, 10]);
        assert_eq!(player.playing(), None);
    }

    #[test]
    fn a_jump_plays_the_other_slot_from_this_ones_last_frame() {
        let store = Store::default()
            .with(0, &[(64, 100)], |header| {
                header.jump_on = true;
                header.jump_slot = 5;
            })
            .with(5, &[(64, 0), (32, 10)], |_| {});
        let mut player = Player::new();
        let cycles = play_out(&mut player, &store, 0, Start::Play, 100);
        assert_eq!(device0(&cycles), [50, 100, 50, 0, 10]);
        assert_eq!(player.playing(), None);
        // Queued, the jump is ignored; plays 2 runs the motion twice.
        let cycles = play_out(&mut Player::new(), &store, 0, Start::Queued { plays: 2 }, 100);
        assert_eq!(device0(&cycles), [50, 100, 100, 100]);
        // Plays 1 disables the motion's own loop.
        let looped = Store::default().with(0, &[(32, 1), (32, 2)], |header| {
            header.loop_on = true;
            header.loop_end = 1;
            header.loop_count = LOOP_FOREVER;
        });
        let cycles = play_out(&mut Player::new(), &looped, 0, Start::Queued { plays: 1 }, 100);
        assert_eq!(device0(&cycles), [1, 2]);
    }

    #[test]
    fn stop_after_last_ends_a_loop_forever_after_its_last_frame() {
        let store = Store::default().with(0, &[(32, 1), (32, 2), (32, 3)], |header| {
            header.loop_on = true;
            header.loop_end = 1;
            header.loop_count = LOOP_FOREVER;
        });
        let mut player = Player::new();
        assert!(player.start(&store, 0, Start::Play));
        let mut seen = Vec::new();
        for _ in 0..5 {
            seen.push(player.cycle(&store).unwrap()[0]);
        }
        player.stop_after_last();
        while let Some(out) = player.cycle(&store) {
            seen.push(out[0]);
        }
        assert_eq!(seen, [1, 2, 1, 2, 1, 2, 3]);
    }

    #[test]
    fn a_zero_count_frame_holds_for_256_cycles_and_outputs_are_clamped() {
        let store = Store::default().with(0, &[(8192, 500)], |_| {});
        let cycles = play_out(&mut Player::new(), &store, 0, Start::Play, 1000);
        assert_eq!(cycles.len(), 256);
        assert!(cycles.iter().all(|out| out[0] == 0));
        assert_eq!(joint_output(500, -900, 900, 600), 900);
        assert_eq!(joint_output(-200, -900, 900, -100), -300);
        assert_eq!(joint_output(0, 100, -100, 500), 100, "min and max swapped in a file");
    }
}
