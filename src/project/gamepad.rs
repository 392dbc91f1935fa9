//! A project's gamepad bindings, one set per family (saved in the project
//! file's optional `gamepad` section): axes that move servos or PLEN2 joints
//! (a range, a dead zone, invert, absolute or rate), and buttons that fire
//! servo actions and macros, PLEN2 motions and play lists, or an rFLEX STOP and
//! brake. They sit beside a servo board's own remote tables, not instead of them.

use serde::{Deserialize, Serialize};

use super::plen2::Joint;

/// The bindings of each family.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GamepadMappings {
    /// For a servo board.
    #[serde(default, skip_serializing_if = "Mapping::is_empty")]
    pub servo: Mapping,
    /// For a PLEN2.
    #[serde(default, skip_serializing_if = "Mapping::is_empty")]
    pub plen2: Mapping,
    /// For an rFLEX base (its buttons; its stick drives through the dead-man).
    #[serde(default, skip_serializing_if = "Mapping::is_empty")]
    pub rflex: Mapping,
}

impl GamepadMappings {
    /// Whether no family has a binding.
    pub fn is_empty(&self) -> bool {
        self.servo.is_empty() && self.plen2.is_empty() && self.rflex.is_empty()
    }
}

/// One family's bindings.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Mapping {
    /// Axes that move a servo or a joint.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub axes: Vec<AxisBinding>,
    /// Buttons that fire something.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub buttons: Vec<ButtonBinding>,
}

impl Mapping {
    /// Whether there is no binding.
    pub fn is_empty(&self) -> bool {
        self.axes.is_empty() && self.buttons.is_empty()
    }

    /// What is bound twice, or to a button another use holds (`reserved`,
    /// e.g. the rFLEX dead-man): each conflict once, as (kind, code).
    pub fn conflicts(&self, reserved: &[u16]) -> Vec<Conflict> {
        let mut conflicts = Vec::new();
        for (index, binding) in self.buttons.iter().enumerate() {
            if reserved.contains(&binding.button) {
                conflicts.push(Conflict::Reserved(binding.button));
            } else if self.buttons[..index].iter().any(|earlier| earlier.button == binding.button)
                && !conflicts.contains(&Conflict::Button(binding.button))
            {
                conflicts.push(Conflict::Button(binding.button));
            }
        }
        for (index, binding) in self.axes.iter().enumerate() {
            let earlier = &self.axes[..index];
            if earlier.iter().any(|other| other.target == binding.target)
                && !conflicts.contains(&Conflict::Target(binding.target))
            {
                conflicts.push(Conflict::Target(binding.target));
            }
        }
        conflicts
    }
}

/// Bindings that cannot all work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Conflict {
    /// A button bound more than once (each press would fire all of them).
    Button(u16),
    /// A button another use holds (the rFLEX dead-man).
    Reserved(u16),
    /// A servo or joint moved by more than one axis (they would fight).
    Target(AxisTarget),
}

/// What an axis moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisTarget {
    /// A servo of the board, by id.
    Servo(u8),
    /// A PLEN2 joint.
    Joint(Joint),
}

/// How an axis moves its target.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisMode {
    /// The axis's position is the angle: its low end `min_deg`, its high end `max_deg`.
    #[default]
    Absolute,
    /// The axis's position is a speed: full deflection turns this many degrees a second.
    Rate {
        /// Degrees a second at full deflection.
        deg_per_s: f64,
    },
}

/// An axis bound to a servo or a joint.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AxisBinding {
    /// The axis (`ABS_RX` = 3, …).
    pub axis: u16,
    /// What it moves.
    pub target: AxisTarget,
    /// The angle at the axis's low end, degrees (absolute), and the least it may reach (rate).
    pub min_deg: f64,
    /// The angle at the axis's high end, degrees (absolute), and the most it may reach (rate).
    pub max_deg: f64,
    /// The part of the axis around its centre that counts as centred, 0..0.9.
    #[serde(default)]
    pub dead_zone: f64,
    /// Low end and high end swapped.
    #[serde(default)]
    pub invert: bool,
    /// Absolute or rate.
    #[serde(default)]
    pub mode: AxisMode,
}

impl AxisBinding {
    /// `axis` moving `target` from `range.0` (its low end) to `range.1`, with a 10 % dead zone.
    pub fn absolute(axis: u16, target: AxisTarget, (min_deg, max_deg): (f64, f64)) -> Self {
        Self { axis, target, min_deg, max_deg, dead_zone: 0.1, invert: false, mode: AxisMode::Absolute }
    }
}

/// A button bound to something it fires when pressed.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ButtonBinding {
    /// The button (`BTN_SOUTH` = 0x130, …).
    pub button: u16,
    /// What it fires.
    pub fire: Fire,
}

/// What a button fires.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Fire {
    /// Play a servo action of the project (live, on the board).
    Action(i32),
    /// Run a macro stored on the servo board.
    Macro(i32),
    /// Play a PLEN2 motion stored on the robot (`$PM`).
    Motion(u8),
    /// Play a PLEN2 play list of the project.
    PlayList(usize),
    /// STOP (every family's own).
    Stop,
    /// Set an rFLEX base's brake.
    Brake,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conflicts_are_named_once_each() {
        let button = |button, fire| ButtonBinding { button, fire };
        let axis = |axis, servo| AxisBinding {
            axis,
            target: AxisTarget::Servo(servo),
            min_deg: -90.0,
            max_deg: 90.0,
            dead_zone: 0.0,
            invert: false,
            mode: AxisMode::Absolute,
        };
        let mapping = Mapping {
            axes: vec![axis(3, 1), axis(4, 1), axis(0, 2)],
            buttons: vec![
                button(0x130, Fire::Action(1)),
                button(0x130, Fire::Action(2)),
                button(0x130, Fire::Macro(2)),
                button(0x136, Fire::Stop),
            ],
        };
        assert_eq!(
            mapping.conflicts(&[0x136]),
            [Conflict::Button(0x130), Conflict::Reserved(0x136), Conflict::Target(AxisTarget::Servo(1))]
        );
        assert!(Mapping::default().conflicts(&[]).is_empty());
    }
}
