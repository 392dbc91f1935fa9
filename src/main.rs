//! The `servo-studio` binary.

use std::process::ExitCode;

use clap::{CommandFactory, Parser};

mod cli;

use cli::{Cli, CliCommand};

fn main() -> ExitCode {
    let args = Cli::parse();
    match args.command {
        Some(CliCommand::Check { file }) => cli::check(&file),
        None => {
            // The editor window arrives with the GUI; until then, show the commands.
            let _ = Cli::command().print_help();
            ExitCode::SUCCESS
        }
    }
}
