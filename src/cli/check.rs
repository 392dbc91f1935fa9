//! `servo-studio check FILE|FOLDER`: every problem with its location (and,
//! in a folder, its file), every folder entry not read with why. The result
//! is decided before anything is printed, and memory stays bounded whatever
//! the file holds (the first thousand problems of each kind are kept, all are
//! counted), so `check FILE | head -1` still exits 1 when the file has errors.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::ExitCode;

use super::out::{self, Unwritten, say};
use crate::project::input::{self, InputKind, OpenError};
use crate::project::motion_json;
use crate::project::{self, Family, Location, Problem, ProblemKind, Problems, Project, Severity};

/// What `check` prints, decided before any of it is.
#[derive(Debug, Default)]
struct Report {
    /// Lines, in order.
    lines: Vec<String>,
    errors: usize,
    warnings: usize,
    /// Problems counted but not listed.
    not_listed: usize,
}

impl Report {
    /// A problem, after `prefix` (a file name) when there is one.
    fn problem(&mut self, prefix: &str, problem: &Problem) {
        let text = problem.to_string();
        self.lines.push(match text.split_once(": ") {
            Some((severity, rest)) if !prefix.is_empty() => format!("{severity}: {prefix}: {rest}"),
            _ => text,
        });
    }

    /// Every problem of `problems`, after `prefix`: the kept ones listed, all counted.
    fn problems(&mut self, prefix: &str, problems: &Problems) {
        for problem in problems {
            self.problem(prefix, problem);
        }
        self.errors += problems.errors();
        self.warnings += problems.warnings();
        self.not_listed += problems.not_kept();
    }

    /// An error that is not a problem of the document (a file that cannot be read).
    fn error(&mut self, text: &str) {
        self.lines.push(format!("error: {text}"));
        self.errors += 1;
    }

    fn code(&self) -> ExitCode {
        if self.errors > 0 { ExitCode::FAILURE } else { ExitCode::SUCCESS }
    }
}

fn unknown_key(path: String) -> Problem {
    Problem { severity: Severity::Warning, location: Location::Key { path }, kind: ProblemKind::UnknownKey }
}

/// The unknown keys of `loaded` as warnings, then its document's problems.
fn loaded_problems(loaded: &project::Loaded) -> Problems {
    let mut problems: Problems = loaded.unknown_keys.iter().cloned().map(unknown_key).collect();
    // Keys counted but not kept by name are warnings all the same.
    for _ in 0..loaded.unknown_keys_not_kept {
        problems.push(unknown_key(String::new()));
    }
    problems.extend(project::validate(&loaded.project));
    problems
}

/// Runs `servo-studio check FILE`.
pub fn run(file: &Path) -> ExitCode {
    let report = if file.is_dir() { folder(file) } else { single(file) };
    let report = match report {
        Ok(report) => report,
        Err(error) => return super::finish(Err(error)),
    };
    let summary = format!("{}: {} error(s), {} warning(s)", file.display(), report.errors, report.warnings);
    let printed = report
        .lines
        .iter()
        .try_for_each(|line| out::line(line))
        .and_then(|()| {
            if report.not_listed == 0 {
                return Ok(());
            }
            out::line(&format!(
                "… {} more problem(s) not listed (the first {} errors and warnings are)",
                report.not_listed,
                Problems::KEPT_PER_SEVERITY
            ))
        })
        .and_then(|()| out::line(&summary));
    match printed {
        // The result was decided before the reader went away (`| head -1`): it stands.
        Ok(()) | Err(Unwritten::Closed) => report.code(),
        Err(error @ Unwritten::Failed(_)) => {
            say!("error: {error}");
            ExitCode::from(error.exit_code())
        }
    }
}

fn single(file: &Path) -> anyhow::Result<Report> {
    if crate::show::Show::is_show_file(file) {
        return show(file);
    }
    let opened = super::open_input(file)?;
    let mut report = Report::default();
    report.problems("", &loaded_problems(&opened.loaded));
    Ok(report)
}

/// A show file (version 3): each device's project checked as a project is
/// (its problems after `device NAME`), then the show's own — names, and every
/// cue against what its device holds.
fn show(file: &Path) -> anyhow::Result<Report> {
    let text = input::read_text(file, input::MAX_PROJECT_BYTES)?;
    let checked = crate::show::checked(&text).map_err(|error| anyhow::anyhow!("{}: {error}", file.display()))?;
    let mut report = Report::default();
    let problems: Problems = checked.unknown_keys.into_iter().map(unknown_key).collect();
    report.problems("", &problems);
    for (name, loaded) in &checked.devices {
        let prefix = format!("device {name:?}");
        match loaded {
            Ok(loaded) => report.problems(&prefix, &loaded_problems(loaded)),
            Err(error) => report.error(&format!("{prefix}: {error}")),
        }
    }
    for problem in &checked.problems {
        report.error(&problem.to_string());
    }
    Ok(report)
}

fn file_name(file: &Path) -> String {
    file.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned())
}

/// A folder: each `*.json` checked as what it is (a project file on its own;
/// motion.json files together, as the slots of one robot), every other entry
/// said with why it was not read.
fn folder(folder: &Path) -> anyhow::Result<Report> {
    let (files, skipped) = input::folder_entries(folder)?;
    let mut report = Report::default();
    for entry in skipped {
        if entry.is_error {
            report.error(&entry.to_string());
        } else {
            report.lines.push(format!("note: {entry}: not checked"));
        }
    }
    if files.is_empty() {
        if report.errors == 0 {
            anyhow::bail!(motion_json::MotionJsonError::Empty { path: folder.to_path_buf() });
        }
        return Ok(report);
    }
    let mut motions = Vec::new();
    let mut slot_files: BTreeMap<u8, Vec<String>> = BTreeMap::new();
    for file in &files {
        let name = file_name(file);
        match input::open(file) {
            Ok(opened) if opened.kind == InputKind::ProjectFile => {
                report.problems(&name, &loaded_problems(&opened.loaded));
            }
            Ok(opened) => {
                let problems: Problems = opened.loaded.unknown_keys.into_iter().map(unknown_key).collect();
                report.problems(&name, &problems);
                for motion in opened.loaded.project.plen2.motions {
                    slot_files.entry(motion.slot).or_default().push(name.clone());
                    motions.push(motion);
                }
            }
            // Said, and the others still checked.
            Err(OpenError::Project { source, .. }) => report.error(&format!("{name}: {source}")),
            Err(error) => report.error(&error.to_string()),
        }
    }
    let project = Project {
        family: Family::Plen2,
        plen2: project::plen2::Plen2Project { motions, ..Default::default() },
        ..Project::default()
    };
    let problems = project::validate(&project);
    for problem in &problems {
        let files = match &problem.location {
            Location::Motion { slot, .. } | Location::Frame { slot, .. } => slot_files.get(slot).map(|f| f.join(", ")),
            _ => None,
        };
        report.problem(&files.unwrap_or_default(), problem);
    }
    report.errors += problems.errors();
    report.warnings += problems.warnings();
    report.not_listed += problems.not_kept();
    Ok(report)
}
