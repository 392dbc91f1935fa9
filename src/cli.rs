//! The command line: argument parsing and the commands that need no board.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use servo_studio::project::{self, Severity};

/// Servo Studio: pose robot servos live, author actions and macros, and back up
/// and upload servo controller boards.
#[derive(Debug, Parser)]
#[command(name = "servo-studio", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Option<CliCommand>,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum CliCommand {
    /// Check a project file and print every problem with its location.
    /// Exits 1 when there is an error (warnings alone exit 0).
    Check {
        /// The project file (.json).
        file: PathBuf,
    },
}

/// Runs `servo-studio check FILE`.
pub fn check(file: &std::path::Path) -> ExitCode {
    let loaded = match project::load(file) {
        Ok(loaded) => loaded,
        Err(error) => {
            eprintln!("error: {}: {error}", file.display());
            return ExitCode::FAILURE;
        }
    };
    let problems = project::validate(&loaded);
    for problem in &problems {
        println!("{problem}");
    }
    let errors = problems
        .iter()
        .filter(|p| p.severity == Severity::Error)
        .count();
    let warnings = problems.len() - errors;
    println!(
        "{}: {errors} error(s), {warnings} warning(s)",
        file.display()
    );
    if errors > 0 {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
