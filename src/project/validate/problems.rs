//! The problems validation found: every one counted, the first thousand of
//! each severity kept, so that a hostile file of millions of problems costs
//! no more memory than a thousand do.

use super::{Problem, Severity};

/// Problems found, in document order: all counted, the first
/// [`Problems::KEPT_PER_SEVERITY`] of each severity kept. Reads as a slice of
/// the kept ones.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Problems {
    kept: Vec<Problem>,
    errors: usize,
    warnings: usize,
}

impl Problems {
    /// How many problems of each severity are kept; the rest are counted.
    pub const KEPT_PER_SEVERITY: usize = 1000;

    /// No problems.
    pub fn new() -> Self {
        Self::default()
    }

    /// Counts `problem`, and keeps it while fewer than the cap of its severity are kept.
    pub fn push(&mut self, problem: Problem) {
        let count = match problem.severity {
            Severity::Error => &mut self.errors,
            Severity::Warning => &mut self.warnings,
        };
        *count += 1;
        if *count <= Self::KEPT_PER_SEVERITY {
            self.kept.push(problem);
        }
    }

    /// Errors found, kept or not.
    pub fn errors(&self) -> usize {
        self.errors
    }

    /// Warnings found, kept or not.
    pub fn warnings(&self) -> usize {
        self.warnings
    }

    /// Problems counted but not kept.
    pub fn not_kept(&self) -> usize {
        self.errors + self.warnings - self.kept.len()
    }

    /// Whether any error was found.
    pub fn has_errors(&self) -> bool {
        self.errors > 0
    }

    /// The errors only (their count included).
    pub fn errors_only(self) -> Self {
        let errors = self.errors;
        let kept = self.kept.into_iter().filter(|problem| problem.severity == Severity::Error).collect();
        Self { kept, errors, warnings: 0 }
    }

    /// The first `shown` kept problems, one per line, and a last line saying
    /// how many more there are, if any.
    pub fn listed(&self, shown: usize) -> String {
        let mut lines: Vec<String> = self.kept.iter().take(shown).map(ToString::to_string).collect();
        let more = self.errors + self.warnings - lines.len();
        if more > 0 {
            lines.push(format!("… and {more} more (servo-studio check lists them)"));
        }
        lines.join("\n")
    }
}

impl std::ops::Deref for Problems {
    type Target = [Problem];

    fn deref(&self) -> &[Problem] {
        &self.kept
    }
}

impl Extend<Problem> for Problems {
    fn extend<I: IntoIterator<Item = Problem>>(&mut self, problems: I) {
        for problem in problems {
            self.push(problem);
        }
    }
}

impl FromIterator<Problem> for Problems {
    fn from_iter<I: IntoIterator<Item = Problem>>(problems: I) -> Self {
        let mut all = Self::new();
        all.extend(problems);
        all
    }
}

impl IntoIterator for Problems {
    type Item = Problem;
    type IntoIter = std::vec::IntoIter<Problem>;

    fn into_iter(self) -> Self::IntoIter {
        self.kept.into_iter()
    }
}

impl<'a> IntoIterator for &'a Problems {
    type Item = &'a Problem;
    type IntoIter = std::slice::Iter<'a, Problem>;

    fn into_iter(self) -> Self::IntoIter {
        self.kept.iter()
    }
}

impl<const N: usize> PartialEq<[Problem; N]> for Problems {
    fn eq(&self, other: &[Problem; N]) -> bool {
        self.not_kept() == 0 && self.kept == other
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::{Location, ProblemKind};

    fn problem(severity: Severity) -> Problem {
        Problem { severity, location: Location::Project, kind: ProblemKind::NoSteps }
    }

    #[test]
    fn every_problem_is_counted_and_the_first_thousand_of_each_severity_kept() {
        let mut problems = Problems::new();
        for _ in 0..3500 {
            problems.push(problem(Severity::Warning));
        }
        problems.push(problem(Severity::Error));
        assert_eq!((problems.errors(), problems.warnings(), problems.len()), (1, 3500, 1001));
        assert!(problems.has_errors(), "an error after many warnings is still kept");
        assert_eq!(problems.last().map(|p| p.severity), Some(Severity::Error));
        assert_eq!(problems.not_kept(), 2500);
        let errors = problems.clone().errors_only();
        assert_eq!((errors.errors(), errors.len(), errors.warnings()), (1, 1, 0));
        let listed = problems.listed(2);
        assert_eq!(listed.lines().count(), 3);
        assert!(listed.ends_with("… and 3499 more (servo-studio check lists them)"), "{listed}");
    }
}
