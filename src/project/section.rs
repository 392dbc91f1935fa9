//! Validation of the sections families added since the first three keep
//! (`kept_section.rs` registers them): their problems are reported after the
//! document's own.

use super::document::Project;
use super::kept_section::Section;
use super::validate::{Location, Problem, ProblemKind, Problems, Severity};

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
