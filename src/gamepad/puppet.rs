//! Gamepad bindings at work: axes move servos or joints (absolute: the
//! axis's position is the angle; rate: it is a speed, integrated over time),
//! within each target's limits, and buttons fire what they are bound to when
//! pressed (once per press; nothing fires from the state a drop leaves).
//! Sans-IO: the pad's states and the time come in, cues go out.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use super::source::PadUpdate;
use super::state::{PadState, dead_zone};
use crate::project::gamepad::{AxisBinding, AxisMode, AxisTarget, Fire, Mapping};

/// What the bindings ask for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cue {
    /// Move a servo or a joint to this angle, degrees (within its limits).
    Move {
        /// What.
        target: AxisTarget,
        /// Where to, degrees.
        degrees: f64,
    },
    /// A button was pressed.
    Fire(Fire),
}

/// Angles are sent in steps of this, degrees (a stick's noise does not flood the link).
const STEP_DEG: f64 = 0.5;

/// The bindings' state (see the module documentation).
#[derive(Debug, Default)]
pub struct Puppeteer {
    state: Option<PadState>,
    /// Where each axis binding (by index) put its target last.
    placed: BTreeMap<usize, f64>,
    /// When rate axes were last moved on.
    integrated_at: Option<Instant>,
}

impl Puppeteer {
    /// A puppeteer that has seen nothing.
    pub fn new() -> Self {
        Self::default()
    }

    /// Takes a gamepad update. `limits` gives each target's range (degrees)
    /// and `now_at` where it is now (where a rate axis starts from).
    pub fn update(
        &mut self,
        mapping: &Mapping,
        at: Instant,
        update: &PadUpdate,
        limits: &dyn Fn(AxisTarget) -> (f64, f64),
        now_at: &dyn Fn(AxisTarget) -> f64,
    ) -> Vec<Cue> {
        let mut cues = self.tick(mapping, at, limits, now_at);
        let PadUpdate::State(state) = update else {
            // Dropped or gone: nothing is known, nothing held; rate axes stop.
            self.state = None;
            return cues;
        };
        for binding in &mapping.buttons {
            let before = self.state.as_ref().is_some_and(|previous| previous.pressed(binding.button));
            if state.pressed(binding.button) && !before {
                cues.push(Cue::Fire(binding.fire));
            }
        }
        for (index, binding) in mapping.axes.iter().enumerate() {
            if binding.mode != AxisMode::Absolute {
                continue;
            }
            let (low, high) = limits(binding.target);
            let degrees = absolute(binding, state).clamp(low.min(high), high.max(low));
            cues.extend(self.place(index, binding.target, degrees));
        }
        self.state = Some(state.clone());
        cues
    }

    /// Whether a rate axis is deflected (the owner keeps ticking).
    pub fn moving(&self, mapping: &Mapping) -> bool {
        let Some(state) = &self.state else { return false };
        mapping
            .axes
            .iter()
            .any(|binding| matches!(binding.mode, AxisMode::Rate { .. }) && deflection(binding, state) != 0.0)
    }

    /// Moves rate axes on to `now` (a stick held still sends no events).
    pub fn tick(
        &mut self,
        mapping: &Mapping,
        now: Instant,
        limits: &dyn Fn(AxisTarget) -> (f64, f64),
        now_at: &dyn Fn(AxisTarget) -> f64,
    ) -> Vec<Cue> {
        let since = self.integrated_at.map_or(Duration::ZERO, |then| now.saturating_duration_since(then));
        self.integrated_at = Some(now);
        let Some(state) = self.state.clone() else { return Vec::new() };
        let mut cues = Vec::new();
        for (index, binding) in mapping.axes.iter().enumerate() {
            let AxisMode::Rate { deg_per_s } = binding.mode else { continue };
            let speed = deflection(binding, &state) * deg_per_s;
            if speed == 0.0 {
                continue;
            }
            let from = self.placed.get(&index).copied().unwrap_or_else(|| now_at(binding.target));
            let (low, high) = limits(binding.target);
            let (low, high) =
                (low.max(binding.min_deg.min(binding.max_deg)), high.min(binding.max_deg.max(binding.min_deg)));
            let degrees = (from + speed * since.as_secs_f64()).clamp(low.min(high), high.max(low));
            // Rate axes keep their exact position; only what is sent is stepped.
            let sent = self.placed.get(&index).map(|placed| (placed / STEP_DEG).round());
            self.placed.insert(index, degrees);
            if sent != Some((degrees / STEP_DEG).round()) {
                cues.push(Cue::Move { target: binding.target, degrees: (degrees / STEP_DEG).round() * STEP_DEG });
            }
        }
        cues
    }

    fn place(&mut self, index: usize, target: AxisTarget, degrees: f64) -> Option<Cue> {
        let stepped = (degrees / STEP_DEG).round() * STEP_DEG;
        if self.placed.get(&index) == Some(&stepped) {
            return None;
        }
        self.placed.insert(index, stepped);
        Some(Cue::Move { target, degrees: stepped })
    }
}

/// The axis's deflection, −1..1, after its dead zone and inversion.
fn deflection(binding: &AxisBinding, state: &PadState) -> f64 {
    let value = dead_zone(state.axis(binding.axis), binding.dead_zone);
    if binding.invert { -value } else { value }
}

/// The angle an absolute axis asks for: its low end `min_deg`, its high end `max_deg`.
fn absolute(binding: &AxisBinding, state: &PadState) -> f64 {
    let t = (deflection(binding, state) + 1.0) / 2.0;
    binding.min_deg + t * (binding.max_deg - binding.min_deg)
}

#[cfg(test)]
mod tests {
    use super::super::event::{ABS_RX, ABS_RY, BTN_SOUTH, RawEvent};
    use super::*;
    use crate::project::gamepad::{ButtonBinding, Fire};
    use crate::project::plen2::Joint;

    fn pad(events: &[RawEvent]) -> PadUpdate {
        let mut state = PadState::default();
        for event in events {
            state.apply(*event);
        }
        state.apply(RawEvent::report());
        PadUpdate::State(state)
    }

    fn mapping() -> Mapping {
        Mapping {
            axes: vec![
                AxisBinding::absolute(ABS_RX, AxisTarget::Joint(Joint::LeftShoulderPitch), (-120.0, 120.0)),
                AxisBinding {
                    axis: ABS_RY,
                    target: AxisTarget::Servo(3),
                    min_deg: -45.0,
                    max_deg: 45.0,
                    dead_zone: 0.0,
                    invert: true,
                    mode: AxisMode::Rate { deg_per_s: 90.0 },
                },
            ],
            buttons: vec![ButtonBinding { button: BTN_SOUTH, fire: Fire::Motion(7) }],
        }
    }

    #[test]
    fn an_absolute_axis_is_the_angle_within_the_targets_limits() {
        let t0 = Instant::now();
        let mut puppet = Puppeteer::new();
        let limits = |_| (-90.0, 90.0);
        let cues = puppet.update(&mapping(), t0, &pad(&[RawEvent::abs(ABS_RX, 32767)]), &limits, &|_| 0.0);
        // The binding asks for 120°; the joint stops at 90°.
        assert_eq!(cues, [Cue::Move { target: AxisTarget::Joint(Joint::LeftShoulderPitch), degrees: 90.0 }]);
        let cues = puppet.update(&mapping(), t0, &pad(&[RawEvent::abs(ABS_RX, -16384)]), &limits, &|_| 0.0);
        // Half the stick left beyond a 10 % dead zone: −0.444…, so −53.3° → −53.5 in 0.5° steps.
        assert_eq!(cues, [Cue::Move { target: AxisTarget::Joint(Joint::LeftShoulderPitch), degrees: -53.5 }]);
        let again = puppet.update(&mapping(), t0, &pad(&[RawEvent::abs(ABS_RX, -16380)]), &limits, &|_| 0.0);
        assert_eq!(again, [], "the same step again is not sent again");
    }

    #[test]
    fn a_rate_axis_moves_while_held_from_where_the_target_is() {
        let t0 = Instant::now();
        let mut puppet = Puppeteer::new();
        let limits = |_| (-90.0, 90.0);
        // Inverted: the stick pushed to its low end turns the servo up at 90°/s.
        puppet.update(&mapping(), t0, &pad(&[RawEvent::abs(ABS_RY, -32768)]), &limits, &|_| 10.0);
        assert!(puppet.moving(&mapping()));
        let cues = puppet.tick(&mapping(), t0 + Duration::from_millis(100), &limits, &|_| 10.0);
        assert_eq!(cues, [Cue::Move { target: AxisTarget::Servo(3), degrees: 19.0 }], "from 10° at 90°/s for 0.1 s");
        // Never past the binding's own range (45°), however long it is held.
        let cues = puppet.tick(&mapping(), t0 + Duration::from_secs(5), &limits, &|_| 10.0);
        assert_eq!(cues, [Cue::Move { target: AxisTarget::Servo(3), degrees: 45.0 }]);
        puppet.update(&mapping(), t0 + Duration::from_secs(5), &PadUpdate::Dropped, &limits, &|_| 10.0);
        assert!(!puppet.moving(&mapping()), "a drop stops a rate axis");
    }

    #[test]
    fn a_button_fires_once_per_press_and_never_from_a_drop() {
        let t0 = Instant::now();
        let mut puppet = Puppeteer::new();
        let limits = |_| (-90.0, 90.0);
        let fired = |cues: Vec<Cue>| cues.into_iter().filter(|cue| matches!(cue, Cue::Fire(_))).count();
        let pressed = pad(&[RawEvent::key(BTN_SOUTH, true)]);
        assert_eq!(fired(puppet.update(&mapping(), t0, &pressed, &limits, &|_| 0.0)), 1);
        assert_eq!(fired(puppet.update(&mapping(), t0, &pressed, &limits, &|_| 0.0)), 0, "held: not again");
        puppet.update(&mapping(), t0, &pad(&[]), &limits, &|_| 0.0);
        assert_eq!(fired(puppet.update(&mapping(), t0, &pressed, &limits, &|_| 0.0)), 1, "pressed again");
        let mut torn = PadState::default();
        torn.apply(RawEvent::dropped());
        torn.apply(RawEvent::report());
        assert_eq!(fired(puppet.update(&mapping(), t0, &PadUpdate::State(torn), &limits, &|_| 0.0)), 0);
    }
}
