//! The rFLEX base's actions: what its panels ask for, applied by its own ui.

use crate::project::Family;
use crate::ui::action::ActionOf;

/// An rFLEX panel's request.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RflexAction {
    /// Drive the base at this velocity (held until changed; 0, 0 stops).
    Drive {
        /// m/s, forward positive.
        speed_m_per_s: f64,
        /// rad/s, left positive.
        turn_rad_per_s: f64,
    },
    /// Choose the robot preset.
    SetRobot(crate::project::rflex::Robot),
    /// Set or release the brake.
    SetBrake(bool),
    /// Turn the sonar ring on or off.
    SetSonar(bool),
    /// Forget the echoes heard so far.
    ClearMap,
}

impl ActionOf for RflexAction {
    const FAMILY: Family = Family::Rflex;

    /// A drive that moves (a stop never waits for Resume), and letting the brake go.
    fn moves_robot(&self) -> bool {
        match self {
            Self::Drive { speed_m_per_s, turn_rad_per_s } => *speed_m_per_s != 0.0 || *turn_rad_per_s != 0.0,
            Self::SetBrake(on) => !on,
            _ => false,
        }
    }
}
