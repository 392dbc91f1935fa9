//! A gamepad's state as its events build it, frame by frame (`SYN_REPORT`),
//! and unknown after `SYN_DROPPED` until the next frame ends: then every
//! button reads released and every axis centred — a held dead-man must be
//! pressed again (safe: a base stops rather than drive on a guess).

use std::collections::{BTreeMap, BTreeSet};

use super::event::{EV_ABS, EV_KEY, EV_SYN, RawEvent, SYN_DROPPED, SYN_REPORT};

/// The range a path's axes are taken to span unless told otherwise.
pub const DEFAULT_RANGE: (i32, i32) = (-32768, 32767);

/// What one event did to the state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// Part of a frame not yet ended.
    Pending,
    /// A frame ended: the state changed (or may have).
    Frame,
    /// Events were lost: the state is unknown until the next frame ends.
    Dropped,
    /// The first frame after a drop ended: the state is known again.
    Resynced,
}

/// A gamepad's buttons and axes.
#[derive(Clone, Debug, PartialEq)]
pub struct PadState {
    pressed: BTreeSet<u16>,
    axes: BTreeMap<u16, i32>,
    ranges: BTreeMap<u16, (i32, i32)>,
    default_range: (i32, i32),
    pending: Vec<RawEvent>,
    dropped: bool,
}

impl Default for PadState {
    fn default() -> Self {
        Self::new(DEFAULT_RANGE)
    }
}

impl PadState {
    /// Nothing pressed, every axis centred; axes span `default_range` unless told their own.
    pub fn new(default_range: (i32, i32)) -> Self {
        Self {
            pressed: BTreeSet::new(),
            axes: BTreeMap::new(),
            ranges: BTreeMap::new(),
            default_range,
            pending: Vec::new(),
            dropped: false,
        }
    }

    /// An axis's own range (an event device says it).
    pub fn set_range(&mut self, code: u16, range: (i32, i32)) {
        self.ranges.insert(code, range);
    }

    /// Takes one event; a frame applies at its `SYN_REPORT`.
    pub fn apply(&mut self, event: RawEvent) -> Step {
        match (event.kind, event.code) {
            (EV_SYN, SYN_DROPPED) => {
                self.dropped = true;
                self.pending.clear();
                self.pressed.clear();
                self.axes.clear();
                Step::Dropped
            }
            (EV_SYN, SYN_REPORT) => {
                let events = std::mem::take(&mut self.pending);
                if self.dropped {
                    // The frame that ends a drop is itself incomplete: discarded.
                    self.dropped = false;
                    return Step::Resynced;
                }
                for event in events {
                    match event.kind {
                        EV_KEY if event.value == 0 => {
                            self.pressed.remove(&event.code);
                        }
                        EV_KEY => {
                            self.pressed.insert(event.code);
                        }
                        _ => {
                            self.axes.insert(event.code, event.value);
                        }
                    }
                }
                Step::Frame
            }
            (EV_KEY | EV_ABS, _) => {
                self.pending.push(event);
                Step::Pending
            }
            _ => Step::Pending,
        }
    }

    /// Whether the state is known (no drop waiting for its frame to end).
    pub fn known(&self) -> bool {
        !self.dropped
    }

    /// Whether a button is held.
    pub fn pressed(&self, code: u16) -> bool {
        self.pressed.contains(&code)
    }

    /// Every button held.
    pub fn buttons(&self) -> impl Iterator<Item = u16> + '_ {
        self.pressed.iter().copied()
    }

    /// An axis, −1 (low end) … 1 (high end), 0 at the middle of its range (and when never moved).
    pub fn axis(&self, code: u16) -> f64 {
        let Some(&value) = self.axes.get(&code) else { return 0.0 };
        let (min, max) = self.ranges.get(&code).copied().unwrap_or(self.default_range);
        if max <= min {
            return 0.0;
        }
        let (min, max, value) = (f64::from(min), f64::from(max), f64::from(value));
        ((value - min) / (max - min) * 2.0 - 1.0).clamp(-1.0, 1.0)
    }

    /// Every axis that has moved, by code.
    pub fn axes(&self) -> impl Iterator<Item = (u16, f64)> + '_ {
        self.axes.keys().map(|code| (*code, self.axis(*code)))
    }
}

/// `value` with a dead zone of `zone` (0..1) around the centre, rescaled so
/// the edge of the zone is 0 and the end stays ±1.
pub fn dead_zone(value: f64, zone: f64) -> f64 {
    let zone = zone.clamp(0.0, 0.95);
    if value.abs() <= zone { 0.0 } else { value.signum() * (value.abs() - zone) / (1.0 - zone) }
}

#[cfg(test)]
mod tests {
    use super::super::event::{ABS_X, ABS_Y, BTN_TL};
    use super::*;

    #[test]
    fn a_frame_applies_at_its_report_and_a_drop_forgets_everything_until_the_next() {
        let mut pad = PadState::default();
        assert_eq!(pad.apply(RawEvent::key(BTN_TL, true)), Step::Pending);
        assert!(!pad.pressed(BTN_TL), "not before its frame ends");
        pad.apply(RawEvent::abs(ABS_Y, -32768));
        assert_eq!(pad.apply(RawEvent::report()), Step::Frame);
        assert!(pad.pressed(BTN_TL));
        assert_eq!(pad.axis(ABS_Y), -1.0);
        assert_eq!(pad.axis(ABS_X), 0.0, "never moved: centred");

        assert_eq!(pad.apply(RawEvent::dropped()), Step::Dropped);
        assert!(!pad.known() && !pad.pressed(BTN_TL));
        // The rest of the torn frame is discarded, even the dead-man in it.
        pad.apply(RawEvent::key(BTN_TL, true));
        assert_eq!(pad.apply(RawEvent::report()), Step::Resynced);
        assert!(pad.known() && !pad.pressed(BTN_TL), "held again only when pressed again");
        assert_eq!(pad.axis(ABS_Y), 0.0);
    }

    #[test]
    fn axes_follow_their_range_and_the_dead_zone_rescales() {
        let mut pad = PadState::new((0, 255));
        pad.set_range(ABS_X, (-100, 100));
        pad.apply(RawEvent::abs(ABS_Y, 255));
        pad.apply(RawEvent::abs(ABS_X, -50));
        pad.apply(RawEvent::report());
        assert_eq!(pad.axis(ABS_Y), 1.0);
        assert_eq!(pad.axis(ABS_X), -0.5);
        assert_eq!(dead_zone(0.1, 0.15), 0.0);
        assert!((dead_zone(-0.575, 0.15) + 0.5).abs() < 1e-9);
        assert_eq!(dead_zone(1.0, 0.15), 1.0);
    }
}
