//! The `servo-studio` binary.

use std::process::ExitCode;

use clap::{CommandFactory, Parser};

mod cli;

use cli::Cli;

fn main() -> ExitCode {
    let args = Cli::parse();
    match args.command {
        Some(command) => cli::run(command),
        None => {
            // The editor window arrives with the GUI; until then, show the commands.
            let _ = Cli::command().print_help();
            ExitCode::SUCCESS
        }
    }
}
