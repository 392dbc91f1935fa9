//! The `servo-studio` binary.

// Output goes through `cli::out`, which never panics when stdout or stderr fail (clippy.toml names the macros).
#![warn(clippy::disallowed_macros)]

use std::process::ExitCode;

use clap::Parser;

mod cli;

use cli::Cli;

fn main() -> ExitCode {
    let args = Cli::parse();
    match args.command {
        Some(command) => cli::run(command),
        None => cli::run(cli::CliCommand::Gui { file: None, demo: false, protocol: None }),
    }
}
