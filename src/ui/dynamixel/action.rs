//! What the DYNAMIXEL panels ask of the editor.

use crate::project::Family;
use crate::project::dynamixel::{DynamixelSection, Profile};
use crate::ui::action::ActionOf;

/// The DYNAMIXEL panels' requests.
#[derive(Clone, Debug, PartialEq)]
pub enum DynamixelAction {
    /// Scans the bus again (both protocols).
    Scan,
    /// Servo `id` to `position` (its own units), clamped to its limits, sent live.
    Goal {
        /// The servo.
        id: u8,
        /// Where to.
        position: u32,
    },
    /// Torque on or off: servo `id`, or (none) every servo.
    Torque {
        /// The servo, or every one.
        id: Option<u8>,
        /// On or off.
        on: bool,
    },
    /// Servo `id`'s LED.
    Led {
        /// The servo.
        id: u8,
        /// Lit or not.
        on: bool,
    },
    /// Servo `id` moves live at `profile`, kept in the project (one undo step).
    Profile {
        /// The servo.
        id: u8,
        /// Its profile.
        profile: Profile,
    },
    /// Where every servo is becomes a step of the motion shown (one undo step).
    Capture,
    /// Starts (true) or ends a recording; its end fits it into a motion (one undo step).
    Record(bool),
    /// Shows motion `index`.
    SelectMotion(usize),
    /// A new, empty motion.
    AddMotion,
    /// The section as a panel edited it (one undo step).
    Edit(Box<DynamixelSection>),
    /// Streams motion `index` to the servos.
    Play(usize),
    /// Every servo's torque off, at once: the robot goes limp.
    Relax,
}

impl ActionOf for DynamixelAction {
    const FAMILY: Family = Family::Dynamixel;

    fn moves_robot(&self) -> bool {
        matches!(self, Self::Goal { .. } | Self::Torque { on: true, .. } | Self::Play(_))
    }
}
