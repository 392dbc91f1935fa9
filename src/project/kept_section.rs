//! The registry of project sections kept by families added since the first
//! three: each family registers its own (`inventory::submit!` in its own
//! files) — its tag, how its section is checked, and what a new project of
//! it keeps. The project file and a new project read it; validation
//! (`section.rs`) asks it for the checks.

use super::family::Family;

/// A family's section of the project, kept under its tag.
#[derive(Debug)]
pub struct Section {
    /// The family.
    pub family: Family,
    /// What is wrong with the section as kept, in the family's words (none: nothing).
    pub check: fn(&serde_json::Value) -> Vec<String>,
    /// The section of a new project of the family (what an empty project file writes under its tag).
    pub fresh: fn() -> serde_json::Value,
}

/// The section a new project of `family` keeps, if the family keeps one.
pub fn fresh(family: Family) -> Option<serde_json::Value> {
    inventory::iter::<Section>.into_iter().find(|section| section.family == family).map(|section| (section.fresh)())
}

inventory::collect!(Section);

/// The tags of every family that keeps a section of its own.
pub fn tags() -> Vec<&'static str> {
    inventory::iter::<Section>.into_iter().map(|section| section.family.tag()).collect()
}
