//! The project sections of families added since the first three: each family
//! registers its own (`inventory::submit!` in its own files) — that it keeps a
//! section under its tag in [`Project::sections`], and how that section is
//! checked. The project file reads and writes them; validation reports their
//! problems after the document's own.

use super::document::Project;
use super::family::Family;
use super::validate::{Location, Problem, ProblemKind, Problems, Severity};

/// A family's section of the project, kept under its tag.
#[derive(Debug)]
pub struct Section {
    /// The family.
    pub family: Family,
    /// What is wrong with the section as kept, in the family's words (none: nothing).
    pub check: fn(&serde_json::Value) -> Vec<String>,
}

inventory::collect!(Section);

/// The tags of every family that keeps a section of its own.
pub fn tags() -> Vec<&'static str> {
    inventory::iter::<Section>.into_iter().map(|section| section.family.tag()).collect()
}

/// Every problem of the project: its own family's typed section and gamepad
/// bindings (`validate::validate`), then its family's kept section, if it
/// registered one (each of those problems an error on the project as a whole).
pub fn validate(project: &Project) -> Problems {
    let mut problems = super::validate::validate(project);
    let family = project.family;
    if let Some(section) = inventory::iter::<Section>.into_iter().find(|section| section.family == family) {
        let kept = project.sections.get(family).cloned().unwrap_or_default();
        problems.extend((section.check)(&kept).into_iter().map(|message| Problem {
            severity: Severity::Error,
            location: Location::Project,
            kind: ProblemKind::Section { message },
        }));
    }
    problems
}
