//! The command line: argument parsing and the commands. Errors are handled
//! here, once: printed with what to try, and turned into the exit status.

mod out;
mod plen2;
mod rflex;
mod servo;
mod signals;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use servo_studio::device;
use servo_studio::project::rflex::Robot;
use servo_studio::project::{self, Family, Severity};

/// Servo Studio: pose robot servos live, author actions and macros, and back up
/// and upload servo controller boards.
#[derive(Debug, Parser)]
#[command(name = "servo-studio", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Option<CliCommand>,
}

fn parse_robot(text: &str) -> Result<Robot, String> {
    match text.to_ascii_lowercase().as_str() {
        "b21r" => Ok(Robot::B21r),
        "atrv-jr" | "atrvjr" => Ok(Robot::AtrvJr),
        "magellan" => Ok(Robot::Magellan),
        _ => Err(format!("{text:?} is not a robot: use b21r, atrv-jr or magellan")),
    }
}

fn parse_family(text: &str) -> Result<Family, String> {
    Family::from_tag(&text.to_ascii_lowercase())
        .ok_or_else(|| format!("{text:?} is not a family: use servo, plen2 or rflex"))
}

/// Where the board is and how to talk to it.
#[derive(Debug, Args)]
pub struct PortArgs {
    /// Serial port (/dev/ttyUSB0, COM3) or tcp://HOST:PORT.
    #[arg(long)]
    pub port: String,
    /// Line rate of a serial port (default: the family's, 115200 for servo boards).
    #[arg(long)]
    pub baud: Option<u32>,
    /// How long the device may take to answer, in milliseconds, on top of
    /// the time the bytes need on the line (default: 1000; 600 for PLEN2).
    #[arg(long)]
    pub timeout_ms: Option<u64>,
    /// The board's family: servo, plen2 or rflex (default: the project file's, else servo).
    #[arg(long, value_parser = parse_family)]
    pub protocol: Option<Family>,
}

impl PortArgs {
    /// The line rate asked for, or the family's default.
    pub fn baud(&self, family: Family) -> u32 {
        self.baud.unwrap_or_else(|| device::line_settings(family).baud)
    }

    /// The timeout asked for, or the family's default, ms.
    pub fn timeout_ms(&self, family: Family) -> u64 {
        self.timeout_ms.unwrap_or(match family {
            Family::Plen2 => 600,
            Family::Servo | Family::Rflex => 1000,
        })
    }
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum CliCommand {
    /// Check a project file (or a PLEN2 motion.json, or a folder of them) and print every problem with its location.
    /// Exits 1 when there is an error (warnings alone exit 0).
    Check {
        /// The project file (.json), motion.json or folder.
        file: PathBuf,
    },
    /// List the serial ports this computer sees.
    Ports,
    /// Run an emulated board. Prints the port to connect to on the first line.
    Sim {
        /// The emulator's options.
        #[command(flatten)]
        args: servo::SimArgs,
        /// Which family to emulate: servo, plen2 or rflex.
        #[arg(long, value_parser = parse_family, default_value = "servo")]
        protocol: Family,
    },
    /// Read everything from a board into a project file.
    Export {
        /// The board.
        #[command(flatten)]
        port: PortArgs,
        /// The project file to write.
        #[arg(long)]
        out: PathBuf,
        /// PLEN2: the slots to read, e.g. 0-19,70 (default: all 90).
        #[arg(long, value_parser = plen2::parse_slots)]
        slots: Option<plen2::Slots>,
    },
    /// Write a project file onto a board: validates, backs the board up,
    /// clears it, writes, and verifies. A file with validation errors (a
    /// backup of content Servo Studio would not author) needs --force.
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
        /// Write even if validation finds errors (restores a backup exactly).
        #[arg(long)]
        force: bool,
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
        /// Start connected to the built-in emulated board (with a sample robot when no file is given).
        #[arg(long)]
        demo: bool,
        /// The board family to start with (default: the project file's, else the last one used).
        #[arg(long, value_parser = parse_family)]
        protocol: Option<Family>,
    },
    /// Drive an rFLEX mobile base, or read its sensors.
    Rflex {
        /// What to do.
        #[command(subcommand)]
        command: rflex::RflexCommand,
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

/// Refuses a family for which `what` does not exist (yet).
fn servo_only(family: Family, what: &str) -> anyhow::Result<()> {
    match family {
        Family::Servo => Ok(()),
        Family::Rflex => anyhow::bail!(
            "{what} does not apply to rFLEX bases (they store no project); use `servo-studio rflex status` to read one and `servo-studio rflex drive` to drive it"
        ),
        Family::Plen2 => anyhow::bail!("{what} for PLEN2 is not in this build of Servo Studio yet"),
    }
}

/// After a failed upload that had begun writing, how to put the device back
/// as the backup holds it (or that there is no backup).
pub fn restore_hint<I>(protocol: &str, port: &str, backup: Option<&std::path::Path>, left: &device::Left<I>) -> String {
    if matches!(left, device::Left::Untouched) {
        return String::new();
    }
    match backup {
        Some(backup) => format!(
            "\nto put it back as it was: servo-studio import{protocol} --port {port} --in {} --force --yes",
            backup.display()
        ),
        None => "\nthere is no backup of what it held (--no-backup)".to_string(),
    }
}

/// Runs a parsed command line.
pub fn run(command: CliCommand) -> ExitCode {
    let result = match command {
        CliCommand::Check { file } => return check(&file),
        CliCommand::Ports => servo::ports(),
        CliCommand::Sim { args, protocol: Family::Rflex } => rflex::sim(&args),
        CliCommand::Sim { args, protocol: Family::Plen2 } => plen2::sim(&args),
        CliCommand::Sim { args, protocol } => servo_only(protocol, "the emulator").and_then(|()| servo::sim(&args)),
        CliCommand::Rflex { command } => rflex::run(&command),
        CliCommand::Export { port, out, slots } => match port.protocol.unwrap_or_default() {
            Family::Plen2 => plen2::export(&port, &out, &slots.map_or_else(|| (0..90).collect(), |slots| slots.0)),
            family => servo_only(family, "export").and_then(|()| servo::export(&port, &out)),
        },
        CliCommand::Import { port, input, yes, force, no_backup, backup_dir } => {
            import(&port, &input, servo::ImportChoices { yes, force, backup_dir: (!no_backup).then_some(backup_dir) })
        }
        CliCommand::Board { command: BoardCommand::Info { port } } => match port.protocol.unwrap_or_default() {
            Family::Plen2 => plen2::info(&port),
            family => servo_only(family, "board info").and_then(|()| servo::info(&port)),
        },
        CliCommand::Gui { file, demo, protocol } => gui(file, demo, protocol),
    };
    finish(result)
}

/// The exit status of a command, with its error printed once.
fn finish(result: anyhow::Result<()>) -> ExitCode {
    let Err(error) = result else { return ExitCode::SUCCESS };
    if error.chain().any(|cause| cause.is::<out::Closed>()) {
        // The reader of stdout went away (`| head -1`): nothing is wrong.
        return ExitCode::SUCCESS;
    }
    eprintln!("error: {error:#}");
    match error.chain().find_map(|cause| cause.downcast_ref::<rflex::Exit>()) {
        Some(rflex::Exit(code)) => ExitCode::from(*code),
        None => ExitCode::FAILURE,
    }
}

fn import(port: &PortArgs, input: &std::path::Path, choices: servo::ImportChoices) -> anyhow::Result<()> {
    let loaded = if port.protocol == Some(Family::Plen2) {
        plen2::load_input(input)?
    } else {
        project::load(input).map_err(|error| anyhow::anyhow!("cannot read {}: {error}", input.display()))?
    };
    let family = port.protocol.unwrap_or(loaded.family);
    if family != loaded.family {
        anyhow::bail!(
            "{} is a {} project but --protocol {family} was given; nothing was written",
            input.display(),
            loaded.family
        );
    }
    if family == Family::Plen2 {
        return plen2::import(port, input, &loaded, choices);
    }
    servo_only(family, "import")?;
    servo::import(port, input, &loaded, choices)
}

/// Opens the editor, with `file` if given; with `demo` and no file, on the sample robot.
pub fn gui(file: Option<PathBuf>, demo: bool, protocol: Option<Family>) -> anyhow::Result<()> {
    let project = match &file {
        // A project file, or the PLEN community's motion.json (one file or a folder).
        Some(path) => Some(plen2::load_input(path)?),
        None => None,
    };
    // A motion.json or a folder of them is not a project file: it is saved as a new project.
    let is_project = file.as_ref().is_some_and(|path| {
        path.is_file()
            && project.as_ref().is_some_and(|p| {
                p.family != Family::Plen2
                    || std::fs::read_to_string(path).is_ok_and(|text| !project::motion_json::looks_like_motion(&text))
            })
    });
    let path = if is_project { file } else { None };
    let start = servo_studio::ui::Start { project, path, demo, family: protocol };
    servo_studio::ui::run(start).map_err(|error| {
        anyhow::anyhow!("cannot open the window: {error}. On Linux, a desktop session (X11 or Wayland) and OpenGL drivers are needed")
    })
}

/// Runs `servo-studio check FILE`.
pub fn check(file: &std::path::Path) -> ExitCode {
    // A project file, a PLEN2 motion.json, or a folder of them.
    let loaded = match plen2::load_input(file) {
        Ok(loaded) => loaded,
        Err(error) => {
            eprintln!("error: {error:#}");
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
