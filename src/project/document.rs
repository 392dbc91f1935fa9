//! The document a project file holds: which family of hardware it is for, and
//! one section per family (format v2, field by field in `docs/project-format.md`).

use super::family::Family;
use super::plen2::Plen2Project;
use super::rflex::RflexProject;
use super::servo::ServoProject;

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
    /// The bindings for `family` (none for a family whose project keeps none).
    pub fn of(&self, family: Family) -> &super::gamepad::Mapping {
        const NONE: &super::gamepad::Mapping = &super::gamepad::Mapping { axes: Vec::new(), buttons: Vec::new() };
        match family {
            Family::Servo => &self.servo,
            Family::Plen2 => &self.plen2,
            Family::Rflex => &self.rflex,
            _ => NONE,
        }
    }

    /// The bindings for `family`, to change (None: a family whose project keeps no bindings).
    pub fn of_mut(&mut self, family: Family) -> Option<&mut super::gamepad::Mapping> {
        match family {
            Family::Servo => Some(&mut self.servo),
            Family::Plen2 => Some(&mut self.plen2),
            Family::Rflex => Some(&mut self.rflex),
            _ => None,
        }
    }
}
