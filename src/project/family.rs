//! The families of hardware Servo Studio speaks to, and their registry: each
//! family adds itself where its own project section lives (the test-only echo
//! board in its own folder), so that no file lists them all.

use serde::{Deserialize, Serialize};

/// A family of hardware Servo Studio speaks to, named by its tag — what files
/// and the command line say (`servo`, `plen2`, `rflex`). Families are
/// constants (`Family::Servo`…), matched like enum variants; a match names the
/// families it serves and says what it does for any other, so a new family is
/// one more constant and one [`Registered`] entry in its own files, not an
/// edit of every match.
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
    /// Every family, in menu order: the ones registered (each where its
    /// project section lives, the test-only echo board in its own folder).
    pub fn all() -> &'static [Self] {
        static ALL: std::sync::OnceLock<Vec<Family>> = std::sync::OnceLock::new();
        ALL.get_or_init(|| {
            let mut registered: Vec<&Registered> = inventory::iter::<Registered>.into_iter().collect();
            registered.sort_by_key(|entry| entry.rank);
            registered.into_iter().map(|entry| entry.family).collect()
        })
    }

    /// Every family's tag, in menu order.
    fn tags() -> &'static [&'static str] {
        static TAGS: std::sync::OnceLock<Vec<&'static str>> = std::sync::OnceLock::new();
        TAGS.get_or_init(|| Self::all().iter().map(|family| family.tag).collect())
    }

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
        Self::all().iter().copied().find(|family| family.tag() == tag)
    }
}

/// A family of the registry: each family adds itself (`inventory::submit!`)
/// beside its project section, so that no file lists them all.
#[derive(Debug)]
pub struct Registered {
    /// The family.
    pub family: Family,
    /// Its place in menus (lowest first).
    pub rank: u8,
}

inventory::collect!(Registered);

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
        let index = Self::all().iter().position(|family| family == self).unwrap_or_default();
        serializer.serialize_unit_variant("Family", u32::try_from(index).unwrap_or_default(), self.tag)
    }
}

impl<'de> Deserialize<'de> for Family {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_enum("Family", Family::tags(), TagVisitor)
    }
}

/// Reads a family's tag: a unit variant (a string in JSON, a bare name in
/// RON), or a plain string.
struct TagVisitor;

impl<'de> serde::de::Visitor<'de> for TagVisitor {
    type Value = Family;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "one of {}", Family::tags().join(", "))
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
