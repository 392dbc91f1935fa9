//! The `servo-studio` binary.

use std::process::ExitCode;

use clap::Parser;

use servo_studio::cli::{self, Cli};

fn main() -> ExitCode {
    let args = Cli::parse();
    match args.command {
        Some(command) => cli::run(command),
        None => cli::run(cli::CliCommand::Gui { file: None, demo: false, protocol: None, import: None, show: None }),
    }
}
