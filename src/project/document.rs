//! The document a project file holds: which family of hardware it is for, and
//! one section per family (format v2, field by field in `docs/project-format.md`).

use serde::{Deserialize, Serialize};

use super::plen2::Plen2Project;
use super::rflex::RflexProject;
use super::servo::ServoProject;

/// A family of hardware Servo Studio speaks to.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Family {
    /// Servo controller boards (`board.md`).
    #[default]
    Servo,
    /// The PLEN2 humanoid (`plen2.md`).
    Plen2,
    /// rFLEX mobile bases: B21r, ATRV, Magellan (`rflex.md`).
    Rflex,
}

impl Family {
    /// Every family, in menu order.
    pub const ALL: [Self; 3] = [Self::Servo, Self::Plen2, Self::Rflex];

    /// The tag used in files and on the command line: `servo`, `plen2`, `rflex`.
    pub fn tag(self) -> &'static str {
        match self {
            Self::Servo => "servo",
            Self::Plen2 => "plen2",
            Self::Rflex => "rflex",
        }
    }

    /// The name shown to people.
    pub fn name(self) -> &'static str {
        match self {
            Self::Servo => "Servo board",
            Self::Plen2 => "PLEN2",
            Self::Rflex => "rFLEX base",
        }
    }

    /// The family with this tag.
    pub fn from_tag(tag: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|family| family.tag() == tag)
    }
}

impl std::fmt::Display for Family {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.tag())
    }
}

/// A whole project: the family it is for and one section per family. Only the
/// family's own section is uploaded; the others are kept as they were.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Project {
    /// Which hardware the project is for.
    pub family: Family,
    /// Servo controller board content.
    pub servo: ServoProject,
    /// PLEN2 content.
    pub plen2: Plen2Project,
    /// rFLEX settings.
    pub rflex: RflexProject,
    /// Gamepad bindings, per family.
    pub gamepad: super::gamepad::GamepadMappings,
}

impl From<ServoProject> for Project {
    fn from(servo: ServoProject) -> Self {
        Self::servo(servo)
    }
}

impl Project {
    /// A servo-board project.
    pub fn servo(servo: ServoProject) -> Self {
        Self { family: Family::Servo, servo, ..Self::default() }
    }

    /// An empty project for `family`.
    pub fn empty(family: Family) -> Self {
        Self { family, ..Self::default() }
    }
}

/// A family's gamepad bindings (here, beside [`Family`]: the bindings
/// themselves know no family).
impl super::gamepad::GamepadMappings {
    /// The bindings for `family`.
    pub fn of(&self, family: Family) -> &super::gamepad::Mapping {
        match family {
            Family::Servo => &self.servo,
            Family::Plen2 => &self.plen2,
            Family::Rflex => &self.rflex,
        }
    }

    /// The bindings for `family`, to change.
    pub fn of_mut(&mut self, family: Family) -> &mut super::gamepad::Mapping {
        match family {
            Family::Servo => &mut self.servo,
            Family::Plen2 => &mut self.plen2,
            Family::Rflex => &mut self.rflex,
        }
    }
}
