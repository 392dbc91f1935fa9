//! The document a project file holds: which family of hardware it is for, and
//! one section per family (format v2, field by field in `docs/project-format.md`).

use std::collections::BTreeMap;

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
    /// The sections of the families added since the first three, by tag.
    pub sections: Sections,
    /// The sound the show is timed to, if any (every family's).
    pub sound: Option<super::SoundTrack>,
}

/// The project sections of families the document does not name by field (the
/// first three — servo, PLEN2, rFLEX — are typed fields, read everywhere by
/// type): each is kept under its family's tag as the JSON its family reads and
/// writes, and registers how it is checked ([`super::kept_section::Section`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sections(BTreeMap<String, serde_json::Value>);

impl Sections {
    /// `family`'s section, as kept.
    pub fn get(&self, family: Family) -> Option<&serde_json::Value> {
        self.0.get(family.tag())
    }

    /// `family`'s section read as `T` (`None` when it has none).
    pub fn read<T: serde::de::DeserializeOwned>(&self, family: Family) -> Result<Option<T>, serde_json::Error> {
        self.get(family).map(|value| T::deserialize(value)).transpose()
    }

    /// Keeps `section` as `family`'s (`null`: it has none).
    pub fn set(&mut self, family: Family, section: serde_json::Value) {
        if section.is_null() {
            self.0.remove(family.tag());
        } else {
            self.0.insert(family.tag().to_string(), section);
        }
    }

    /// Every section kept, by tag.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &serde_json::Value)> {
        self.0.iter().map(|(tag, section)| (tag.as_str(), section))
    }
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
        let mut project = Self { family, ..Self::default() };
        if let Some(section) = super::kept_section::fresh(family) {
            project.sections.set(family, section);
        }
        project
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
