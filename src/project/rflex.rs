//! The rFLEX section of a project: which robot (its conversion constants) and
//! how the user likes to drive it.

use serde::{Deserialize, Serialize};

use crate::protocol::rflex::{ATRV_JR, B21R, Conversion, MAGELLAN};

/// Everything an rFLEX project holds.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RflexProject {
    /// The robot.
    #[serde(default)]
    pub robot: Robot,
    /// Drive limits and start-up choices.
    #[serde(default)]
    pub drive: DriveSettings,
}

impl RflexProject {
    /// The fastest the base is ever driven, as the editor drives it: the
    /// project's drive settings, never past what the robot's preset allows
    /// (a setting that is not a number, or not above zero, counts as zero).
    pub fn limits(&self) -> SpeedLimits {
        let robot = self.robot.limits();
        let within = |asked: f64, most: f64| if asked.is_finite() { asked.clamp(0.0, most) } else { 0.0 };
        SpeedLimits {
            max_speed_m_per_s: within(self.drive.max_speed_m_per_s, robot.max_speed_m_per_s),
            max_turn_rad_per_s: within(self.drive.max_turn_rad_per_s, robot.max_turn_rad_per_s),
            max_accel_m_per_s2: within(self.drive.accel_m_per_s2, robot.max_accel_m_per_s2),
        }
    }
}

impl SpeedLimits {
    /// (speed m/s, turn rad/s) held within these limits; NaN is a stop.
    pub fn hold(&self, speed_m_per_s: f64, turn_rad_per_s: f64) -> (f64, f64) {
        let within = |asked: f64, most: f64| if asked.is_nan() { 0.0 } else { asked.clamp(-most, most) };
        (within(speed_m_per_s, self.max_speed_m_per_s), within(turn_rad_per_s, self.max_turn_rad_per_s))
    }
}

/// A robot preset, or custom conversion constants.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "preset", rename_all = "kebab-case")]
pub enum Robot {
    /// RWI / iRobot B21r.
    #[default]
    B21r,
    /// ATRV-Jr.
    AtrvJr,
    /// Magellan.
    Magellan,
    /// Another base, with its own constants.
    Custom {
        /// Distance units per metre.
        distance_units_per_m: f64,
        /// Angle units per radian.
        angle_units_per_rad: f64,
        /// Volts added to raw / 100.
        power_offset_volts: f64,
    },
}

impl Robot {
    /// The robot's conversion constants.
    pub fn conversion(self) -> Conversion {
        match self {
            Self::B21r => B21R,
            Self::AtrvJr => ATRV_JR,
            Self::Magellan => MAGELLAN,
            // Choice: a custom base's sensors are taken as a B21r's (rflex.md §6 gives no other).
            Self::Custom { distance_units_per_m, angle_units_per_rad, power_offset_volts } => {
                Conversion { distance_units_per_m, angle_units_per_rad, power_offset_volts, layout: B21R.layout }
            }
        }
    }
}

/// The fastest a robot is ever driven: what its preset allows (Servo Studio's
/// choice, see `docs/rflex.md`), whatever a user asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpeedLimits {
    /// Translation, m/s.
    pub max_speed_m_per_s: f64,
    /// Rotation, rad/s.
    pub max_turn_rad_per_s: f64,
    /// Translational acceleration, m/s².
    pub max_accel_m_per_s2: f64,
}

impl Robot {
    /// The robot's name as the command line spells it.
    pub fn name(self) -> &'static str {
        match self {
            Self::B21r => "b21r",
            Self::AtrvJr => "atrv-jr",
            Self::Magellan => "magellan",
            Self::Custom { .. } => "custom",
        }
    }

    /// The fastest this robot is driven.
    pub fn limits(self) -> SpeedLimits {
        let (speed, turn, accel) = match self {
            Self::B21r => (1.0, 1.5, 1.0),
            Self::AtrvJr => (1.5, 2.0, 1.5),
            Self::Magellan => (1.0, 2.0, 1.0),
            Self::Custom { .. } => (1.0, 1.5, 1.0),
        };
        SpeedLimits { max_speed_m_per_s: speed, max_turn_rad_per_s: turn, max_accel_m_per_s2: accel }
    }
}

/// How the Drive panel and `rflex drive` limit the base.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DriveSettings {
    /// Fastest translation the pad or keys ask for, m/s.
    pub max_speed_m_per_s: f64,
    /// Fastest rotation, rad/s.
    pub max_turn_rad_per_s: f64,
    /// Translational acceleration sent with each command, m/s².
    pub accel_m_per_s2: f64,
    /// Turn the sonar ring on when connecting.
    pub sonar_on_connect: bool,
}

impl Default for DriveSettings {
    fn default() -> Self {
        Self { max_speed_m_per_s: 0.5, max_turn_rad_per_s: 1.0, accel_m_per_s2: 0.5, sonar_on_connect: true }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_base_is_limited_by_its_project_and_never_past_its_robot() {
        let mut project = RflexProject::default();
        assert_eq!(project.limits().hold(50.0, -1e308), (0.5, -1.0), "the project's 0.5 m/s and 1 rad/s");
        project.drive.max_speed_m_per_s = 9.0;
        project.drive.max_turn_rad_per_s = f64::INFINITY;
        assert_eq!(project.limits().hold(50.0, 9.0), (1.0, 0.0), "a B21r: 1 m/s; an infinite setting counts as 0");
        assert_eq!(project.limits().hold(f64::NAN, 0.2), (0.0, 0.0));
        assert_eq!(project.limits().hold(-0.3, 0.0), (-0.3, 0.0), "within the limits: as asked");
    }
}

// The registry of families: rFLEX bases, where their section of the project lives.
inventory::submit! {
    super::family::Registered { family: super::family::Family::Rflex, rank: 2 }
}
