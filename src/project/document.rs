//! The document a project file holds: which family of hardware it is for, and
//! one section per family (format v2, field by field in `docs/project-format.md`).

use serde::{Deserialize, Serialize};

use super::plen2::Plen2Project;
use super::rflex::RflexProject;
use super::servo::ServoProject;

/// A family of hardware Servo Studio speaks to, named by its tag — what files
/// and the command line say (`servo`, `plen2`, `rflex`). Families are
/// constants (`Family::Servo`…), matched like enum variants; a match names the
/// families it serves and says what it does for any other, so a new family is
/// one more constant and one more entry of [`Family::ALL`], not an edit of
/// every match.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Family {
    tag: &'static str,
    name: &'static str,
}

#[allow(non_upper_case_globals)]
impl Family {
    /// Servo controller boards (`board.md`).
    pub const Servo: Self = Self::named("servo", "Servo board");
    /// The PLEN2 humanoid (`plen2.md`).
    pub const Plen2: Self = Self::named("plen2", "PLEN2");
    /// rFLEX mobile bases: B21r, ATRV, Magellan (`rflex.md`).
    pub const Rflex: Self = Self::named("rflex", "rFLEX base");
    /// The test-only echo board (`ui::echo`): one servo, moved live, that answers every move.
    #[cfg(test)]
    pub const Echo: Self = Self::named("echo", "Echo board");

    /// Every family, in menu order.
    #[cfg(not(test))]
    pub const ALL: [Self; 3] = [Self::Servo, Self::Plen2, Self::Rflex];
    /// Every family, in menu order.
    #[cfg(test)]
    pub const ALL: [Self; 4] = [Self::Servo, Self::Plen2, Self::Rflex, Self::Echo];

    /// A family with this tag and this name for people.
    pub const fn named(tag: &'static str, name: &'static str) -> Self {
        Self { tag, name }
    }

    /// The tag used in files and on the command line: `servo`, `plen2`, `rflex`.
    pub fn tag(self) -> &'static str {
        self.tag
    }

    /// The name shown to people.
    pub fn name(self) -> &'static str {
        self.name
    }

    /// The family with this tag.
    pub fn from_tag(tag: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|family| family.tag() == tag)
    }
}

impl Default for Family {
    fn default() -> Self {
        Self::Servo
    }
}

/// As its constant is named: `Servo`, `Plen2`, `Rflex`.
impl std::fmt::Debug for Family {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut letters = self.tag.chars();
        if let Some(first) = letters.next() {
            write!(f, "{}{}", first.to_ascii_uppercase(), letters.as_str())?;
        }
        Ok(())
    }
}

/// Written as a unit variant named by its tag, as when `Family` was an enum:
/// `"plen2"` in a project file (JSON), `plen2` in the remembered settings (RON).
impl Serialize for Family {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let index = Self::ALL.iter().position(|family| family == self).unwrap_or_default();
        serializer.serialize_unit_variant("Family", u32::try_from(index).unwrap_or_default(), self.tag)
    }
}

impl<'de> Deserialize<'de> for Family {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        const TAGS: &[&str] = &[
            "servo",
            "plen2",
            "rflex",
            #[cfg(test)]
            "echo",
        ];
        deserializer.deserialize_enum("Family", TAGS, TagVisitor)
    }
}

/// Reads a family's tag: a unit variant (a string in JSON, a bare name in
/// RON), or a plain string.
struct TagVisitor;

impl<'de> serde::de::Visitor<'de> for TagVisitor {
    type Value = Family;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let tags: Vec<&str> = Family::ALL.iter().map(|family| family.tag).collect();
        write!(f, "one of {}", tags.join(", "))
    }

    fn visit_str<E: serde::de::Error>(self, tag: &str) -> Result<Family, E> {
        Family::from_tag(tag).ok_or_else(|| E::invalid_value(serde::de::Unexpected::Str(tag), &self))
    }

    fn visit_enum<A: serde::de::EnumAccess<'de>>(self, data: A) -> Result<Family, A::Error> {
        use serde::de::VariantAccess;
        let (Name(tag), variant) = data.variant()?;
        variant.unit_variant()?;
        self.visit_str(&tag)
    }
}

/// A variant's name, read as an identifier (RON writes it bare).
struct Name(String);

impl<'de> Deserialize<'de> for Name {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct NameVisitor;
        impl serde::de::Visitor<'_> for NameVisitor {
            type Value = Name;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a family's tag")
            }
            fn visit_str<E: serde::de::Error>(self, name: &str) -> Result<Name, E> {
                Ok(Name(name.to_owned()))
            }
        }
        deserializer.deserialize_identifier(NameVisitor)
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
