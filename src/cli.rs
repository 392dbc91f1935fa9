//! The command line: argument parsing and the commands. Errors are handled
//! here, once: printed with what to try, and turned into the exit status.

mod board;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use servo_studio::link::DEFAULT_BAUD;
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

/// Where the board is and how to talk to it.
#[derive(Debug, Args)]
pub struct PortArgs {
    /// Serial port (/dev/ttyUSB0, COM3) or tcp://HOST:PORT.
    #[arg(long)]
    pub port: String,
    /// Line rate of a serial port.
    #[arg(long, default_value_t = DEFAULT_BAUD)]
    pub baud: u32,
    /// How long to wait for each response, in milliseconds.
    #[arg(long, default_value_t = 1000)]
    pub timeout_ms: u64,
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
    /// List the serial ports this computer sees.
    Ports,
    /// Run the emulated board. Prints the port to connect to on the first line.
    Sim(board::SimArgs),
    /// Read everything from a board into a project file.
    Export {
        /// The board.
        #[command(flatten)]
        port: PortArgs,
        /// The project file to write.
        #[arg(long)]
        out: PathBuf,
    },
    /// Write a project file onto a board: validates, backs the board up,
    /// clears it, writes, and verifies.
    Import {
        /// The board.
        #[command(flatten)]
        port: PortArgs,
        /// The project file to upload.
        #[arg(long = "in")]
        input: PathBuf,
        /// Do not ask for confirmation.
        #[arg(long)]
        yes: bool,
        /// Do not save a backup of the board first.
        #[arg(long)]
        no_backup: bool,
        /// Folder for the backup (default: the current folder).
        #[arg(long, default_value = ".")]
        backup_dir: PathBuf,
    },
    /// Open the editor window (the default with no command).
    Gui {
        /// A project file to open.
        file: Option<PathBuf>,
        /// Start connected to the built-in emulated board.
        #[arg(long)]
        demo: bool,
    },
    /// Board status.
    Board {
        /// What to show.
        #[command(subcommand)]
        command: BoardCommand,
    },
}

/// `servo-studio board …`
#[derive(Debug, Subcommand)]
pub enum BoardCommand {
    /// Project id, memory, battery and servos.
    Info {
        /// The board.
        #[command(flatten)]
        port: PortArgs,
    },
}

/// Runs a parsed command line.
pub fn run(command: CliCommand) -> ExitCode {
    let result = match command {
        CliCommand::Check { file } => return check(&file),
        CliCommand::Ports => board::ports(),
        CliCommand::Sim(args) => board::sim(&args),
        CliCommand::Export { port, out } => board::export(&port, &out),
        CliCommand::Import { port, input, yes, no_backup, backup_dir } => {
            board::import(&port, &input, yes, (!no_backup).then_some(backup_dir))
        }
        CliCommand::Board { command: BoardCommand::Info { port } } => board::info(&port),
        CliCommand::Gui { file, demo } => gui(file, demo),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}

/// Opens the editor, with `file` if given.
pub fn gui(file: Option<PathBuf>, demo: bool) -> anyhow::Result<()> {
    let project = match &file {
        Some(path) => project::load(path).map_err(|error| anyhow::anyhow!("{}: {error}", path.display()))?,
        None => project::Project::default(),
    };
    servo_studio::ui::run(project, file, demo).map_err(|error| {
        anyhow::anyhow!("cannot open the window: {error}. On Linux, a desktop session (X11 or Wayland) and OpenGL drivers are needed")
    })
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
    let errors = problems.iter().filter(|p| p.severity == Severity::Error).count();
    let warnings = problems.len() - errors;
    println!("{}: {errors} error(s), {warnings} warning(s)", file.display());
    if errors > 0 { ExitCode::FAILURE } else { ExitCode::SUCCESS }
}
