//! A mobile base driven from a gamepad, as teleop users expect (ROS's
//! `teleop_twist_joy`): hold the dead-man button and the left stick drives —
//! up forward, left turns left — scaled to the base's top speeds, with a dead
//! zone. Anything else stops it at once: the dead-man released, the stick
//! centred, a drop in the gamepad's events (until they are known again), the
//! gamepad gone, and whatever the owner says (STOP, lost focus, a signal).
//! Sans-IO: time and the gamepad's updates come in, orders go out.

use std::time::{Duration, Instant};

use super::event::{ABS_X, ABS_Y, BTN_TL};
use super::source::PadUpdate;
use super::state::{PadState, dead_zone};

/// How the pad drives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TeleopConfig {
    /// The button that must be held to drive (`BTN_TL`, the left shoulder).
    pub deadman: u16,
    /// The axis for forward / back (`ABS_Y`: up, its low end, is forward).
    pub speed_axis: u16,
    /// The axis for turning (`ABS_X`: left, its low end, turns left).
    pub turn_axis: u16,
    /// The part of each axis around its centre that counts as centred, 0..1.
    pub dead_zone: f64,
    /// Full stick forward, m/s.
    pub max_speed_m_per_s: f64,
    /// Full stick to the side, rad/s.
    pub max_turn_rad_per_s: f64,
}

impl Default for TeleopConfig {
    fn default() -> Self {
        Self {
            deadman: BTN_TL,
            speed_axis: ABS_Y,
            turn_axis: ABS_X,
            dead_zone: 0.15,
            max_speed_m_per_s: 0.5,
            max_turn_rad_per_s: 1.0,
        }
    }
}

/// Why the base is told to stop.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    /// The dead-man button is not held.
    Released,
    /// The stick is centred.
    Centred,
    /// The gamepad's events were lost: its state is unknown.
    Dropped,
    /// The gamepad is gone (end of input, unplugged, a read error).
    Gone,
    /// The owner said so: STOP, the window lost focus, a signal.
    Halted,
}

/// What the base is to be told.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Order {
    /// Hold this velocity (re-sent at the base's 10 Hz by its driver).
    Drive {
        /// m/s, forward positive.
        speed_m_per_s: f64,
        /// rad/s, left positive.
        turn_rad_per_s: f64,
    },
    /// Stop now.
    Stop(StopReason),
}

/// A change of velocity goes out at most this often (a stick sends hundreds
/// of events a second; the base ignores commands sent too rapidly). A stop
/// never waits.
pub const CHANGE_EVERY: Duration = Duration::from_millis(50);
/// Velocities are sent in steps of this (m/s and rad/s).
const QUANTUM: f64 = 0.01;

/// The teleop state (see the module documentation).
#[derive(Debug)]
pub struct Teleop {
    config: TeleopConfig,
    /// What the base was last told to hold (`None`: stopped, or never driven).
    driving: Option<(f64, f64)>,
    last_change: Option<Instant>,
    /// A velocity change waiting for [`CHANGE_EVERY`] to pass.
    pending: Option<(f64, f64)>,
    /// Halted by the owner: the dead-man must be let go and pressed again to drive.
    latched: bool,
}

impl Teleop {
    /// A teleop that has not driven.
    pub fn new(config: TeleopConfig) -> Self {
        Self { config, driving: None, last_change: None, pending: None, latched: false }
    }

    /// Its configuration.
    pub fn config(&self) -> &TeleopConfig {
        &self.config
    }

    /// Whether the base is being driven.
    pub fn driving(&self) -> bool {
        self.driving.is_some()
    }

    /// What the pad asks for: a velocity, or a stop and why.
    pub fn wanted(&self, state: &PadState) -> Result<(f64, f64), StopReason> {
        if !state.known() {
            return Err(StopReason::Dropped);
        }
        if !state.pressed(self.config.deadman) {
            return Err(StopReason::Released);
        }
        let forward = -dead_zone(state.axis(self.config.speed_axis), self.config.dead_zone);
        let left = -dead_zone(state.axis(self.config.turn_axis), self.config.dead_zone);
        if forward == 0.0 && left == 0.0 {
            return Err(StopReason::Centred);
        }
        let step = |value: f64| (value / QUANTUM).round() * QUANTUM;
        // + 0.0: a centred axis is 0, not −0.
        Ok((step(forward * self.config.max_speed_m_per_s) + 0.0, step(left * self.config.max_turn_rad_per_s) + 0.0))
    }

    /// Takes a gamepad update at `now`; returns what the base must be told now, if anything.
    pub fn update(&mut self, now: Instant, update: &PadUpdate) -> Option<Order> {
        let wanted = match update {
            PadUpdate::State(state) if self.latched => {
                // After a halt, only a fresh press of the dead-man drives again.
                self.latched = state.pressed(self.config.deadman);
                Err(StopReason::Halted)
            }
            PadUpdate::State(state) => self.wanted(state),
            PadUpdate::Dropped => {
                // Events were lost: whatever state is read back afterwards (a
                // device's resynchronisation replays what it finds held), only
                // a dead-man let go and pressed again drives.
                self.latched = true;
                Err(StopReason::Dropped)
            }
            PadUpdate::Gone(_) => Err(StopReason::Gone),
        };
        match wanted {
            Err(reason) => self.stop(reason),
            Ok(velocity) => self.drive(now, velocity),
        }
    }

    /// The owner stops the base (STOP, lost focus, a signal): told at once
    /// while driving; it drives again only once the dead-man is let go and
    /// pressed again.
    pub fn halt(&mut self) -> Option<Order> {
        self.latched = true;
        self.stop(StopReason::Halted)
    }

    fn stop(&mut self, reason: StopReason) -> Option<Order> {
        self.pending = None;
        self.driving.take().map(|_| Order::Stop(reason))
    }

    fn drive(&mut self, now: Instant, velocity: (f64, f64)) -> Option<Order> {
        if self.driving == Some(velocity) {
            self.pending = None;
            return None;
        }
        if self.last_change.is_some_and(|last| now < last + CHANGE_EVERY) && self.driving.is_some() {
            self.pending = Some(velocity);
            return None;
        }
        self.send(now, velocity)
    }

    fn send(&mut self, now: Instant, (speed_m_per_s, turn_rad_per_s): (f64, f64)) -> Option<Order> {
        self.pending = None;
        self.driving = Some((speed_m_per_s, turn_rad_per_s));
        self.last_change = Some(now);
        Some(Order::Drive { speed_m_per_s, turn_rad_per_s })
    }

    /// While the owner does not let the pad drive (after [`Teleop::halt`]):
    /// follows the dead-man only, so that driving again takes a press made
    /// once it is allowed.
    pub fn follow(&mut self, update: &PadUpdate) {
        self.latched = match update {
            PadUpdate::State(state) => state.pressed(self.config.deadman),
            PadUpdate::Dropped | PadUpdate::Gone(_) => true,
        };
    }

    /// When a held-back change is due.
    pub fn poll_timeout(&self) -> Option<Instant> {
        self.pending.and(self.last_change).map(|last| last + CHANGE_EVERY)
    }

    /// A held-back change, once due.
    pub fn poll(&mut self, now: Instant) -> Option<Order> {
        let due = self.poll_timeout().is_some_and(|due| now >= due);
        let velocity = self.pending.filter(|_| due)?;
        self.send(now, velocity)
    }
}

#[cfg(test)]
mod tests {
    use super::super::event::{BTN_SOUTH, RawEvent};
    use super::*;

    fn state(events: &[RawEvent]) -> PadState {
        let mut state = PadState::default();
        for event in events {
            state.apply(*event);
        }
        state.apply(RawEvent::report());
        state
    }

    #[test]
    fn the_stick_drives_only_while_the_dead_man_is_held() {
        let t0 = Instant::now();
        let mut teleop = Teleop::new(TeleopConfig::default());
        // Full up and full left without the dead-man: nothing at all is sent.
        let no_deadman = state(&[RawEvent::abs(ABS_Y, -32768), RawEvent::abs(ABS_X, -32768)]);
        assert_eq!(teleop.update(t0, &PadUpdate::State(no_deadman.clone())), None);
        let mut held = no_deadman;
        held.apply(RawEvent::key(BTN_TL, true));
        held.apply(RawEvent::report());
        assert_eq!(
            teleop.update(t0, &PadUpdate::State(held.clone())),
            Some(Order::Drive { speed_m_per_s: 0.5, turn_rad_per_s: 1.0 }),
            "up is forward, left is a left turn, at the top speeds"
        );
        // Another button changes nothing.
        held.apply(RawEvent::key(BTN_SOUTH, true));
        held.apply(RawEvent::report());
        assert_eq!(teleop.update(t0 + Duration::from_millis(60), &PadUpdate::State(held.clone())), None);
        held.apply(RawEvent::key(BTN_TL, false));
        held.apply(RawEvent::report());
        let released = teleop.update(t0 + Duration::from_millis(61), &PadUpdate::State(held));
        assert_eq!(released, Some(Order::Stop(StopReason::Released)), "at once, not at the next 50 ms");
    }

    #[test]
    fn centring_a_drop_and_the_end_each_stop_and_changes_are_paced_but_stops_are_not() {
        let t0 = Instant::now();
        let mut teleop = Teleop::new(TeleopConfig::default());
        let half = state(&[RawEvent::key(BTN_TL, true), RawEvent::abs(ABS_Y, -16384)]);
        let Some(Order::Drive { speed_m_per_s, .. }) = teleop.update(t0, &PadUpdate::State(half)) else { panic!() };
        assert!((speed_m_per_s - 0.21).abs() < 1e-9, "half the stick beyond a 15 % dead zone: {speed_m_per_s}");
        // A change 10 ms later waits for the 50 ms; the stop does not.
        let full = state(&[RawEvent::key(BTN_TL, true), RawEvent::abs(ABS_Y, -32768)]);
        assert_eq!(teleop.update(t0 + Duration::from_millis(10), &PadUpdate::State(full)), None);
        assert_eq!(teleop.poll_timeout(), Some(t0 + CHANGE_EVERY));
        assert_eq!(teleop.poll(t0 + CHANGE_EVERY), Some(Order::Drive { speed_m_per_s: 0.5, turn_rad_per_s: 0.0 }));
        let centred = state(&[RawEvent::key(BTN_TL, true), RawEvent::abs(ABS_Y, 100)]);
        let at = t0 + Duration::from_millis(51);
        assert_eq!(teleop.update(at, &PadUpdate::State(centred)), Some(Order::Stop(StopReason::Centred)));
        let full = state(&[RawEvent::key(BTN_TL, true), RawEvent::abs(ABS_Y, -32768)]);
        assert!(
            teleop.update(at, &PadUpdate::State(full.clone())).is_some(),
            "a stop does not hold back the next drive"
        );
        assert_eq!(teleop.update(at, &PadUpdate::Dropped), Some(Order::Stop(StopReason::Dropped)));
        // After a drop the dead-man is let go and pressed again to drive.
        teleop.update(at + CHANGE_EVERY, &PadUpdate::State(state(&[RawEvent::abs(ABS_Y, -32768)])));
        assert!(teleop.update(at + CHANGE_EVERY, &PadUpdate::State(full)).is_some(), "pressed again: drives");
        let gone = PadUpdate::Gone(super::super::source::Gone::Ended);
        assert_eq!(teleop.update(at + CHANGE_EVERY, &gone), Some(Order::Stop(StopReason::Gone)));
        assert_eq!(teleop.halt(), None, "already stopped: nothing more");
    }

    #[test]
    fn after_a_halt_the_dead_man_must_be_pressed_again() {
        let t0 = Instant::now();
        let mut teleop = Teleop::new(TeleopConfig::default());
        let full = PadUpdate::State(state(&[RawEvent::key(BTN_TL, true), RawEvent::abs(ABS_Y, -32768)]));
        assert!(teleop.update(t0, &full).is_some());
        assert_eq!(teleop.halt(), Some(Order::Stop(StopReason::Halted)));
        assert_eq!(teleop.update(t0 + CHANGE_EVERY, &full), None, "still held from before the halt");
        let let_go = PadUpdate::State(state(&[RawEvent::abs(ABS_Y, -32768)]));
        assert_eq!(teleop.update(t0 + CHANGE_EVERY, &let_go), None);
        assert!(teleop.update(t0 + CHANGE_EVERY * 2, &full).is_some(), "pressed again: drives");
    }
}
