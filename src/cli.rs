//! The command line: argument parsing and the commands. Errors are handled
//! here, once: printed with what to try, and turned into the exit status.

mod out;
mod plen2;
mod rflex;
mod servo;
mod signals;
mod trajectory;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use servo_studio::device;
use servo_studio::project::rflex::Robot;
use servo_studio::project::{self, Family, Project, Severity};

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
    /// PLEN2: how uploads are paced — fast, adaptive (widens when the link
    /// shows it is late or bursty) or safe (the official 32 bytes, then 50 ms).
    #[arg(long, default_value = "adaptive")]
    pub pacing: device::plen2::PacingMode,
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
    /// Write what the robot outputs over time to a CSV file, one row per board
    /// update: PLEN2, one per 32.768 ms cycle from `$PM` (the frame value in
    /// tenths of a degree relative to home, before clamping); servo board, one
    /// per 10 ms (the angle in degrees). `t_ms`, then one column per joint or servo.
    #[command(group = clap::ArgGroup::new("subject").required(true).args(["slot", "action", "macro_id"]))]
    Trajectory {
        /// The project file (or a PLEN2 motion.json, or a folder of them).
        file: PathBuf,
        /// PLEN2: the motion's slot.
        #[arg(long)]
        slot: Option<u8>,
        /// Servo board: the action's id.
        #[arg(long)]
        action: Option<i32>,
        /// Servo board: the macro's id.
        #[arg(long = "macro")]
        macro_id: Option<i32>,
        /// PLEN2: the motion played before (its last frame is where this one starts; default: power-up, all zeros).
        #[arg(long, requires = "slot")]
        from_slot: Option<u8>,
        /// At most this long (a loop that runs forever stops here).
        #[arg(long, default_value_t = 30.0)]
        seconds: f64,
        /// The CSV file to write.
        #[arg(long)]
        out: PathBuf,
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

/// An error with advice after it (how to restore the device), keeping the
/// error's causes for whoever reads the chain.
#[derive(Debug)]
pub struct Advised<E> {
    /// The error.
    pub error: E,
    /// What to do, appended to its text.
    pub advice: String,
}

impl<E: std::fmt::Display> std::fmt::Display for Advised<E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}{}", self.error, self.advice)
    }
}

impl<E: std::error::Error> std::error::Error for Advised<E> {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.error.source()
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
        CliCommand::Trajectory { file, slot, action, macro_id, from_slot, seconds, out } => {
            let subject = match (slot, action, macro_id) {
                (Some(slot), _, _) => trajectory::Subject::Slot { slot, from_slot },
                (_, Some(action), _) => trajectory::Subject::Action(action),
                (_, _, Some(id)) => trajectory::Subject::Macro(id),
                // clap requires one of them.
                (None, None, None) => trajectory::Subject::Action(0),
            };
            trajectory::run(&file, subject, seconds, &out).and_then(|(rows, covered)| {
                Ok(out::line(&format!("wrote {rows} rows ({covered:.3} s) to {}", out.display()))?)
            })
        }
    };
    finish(result)
}

/// An error and its causes, each said once: a cause whose words its
/// wrapper already carries (`action 3: no response` over `no response`) is
/// not repeated.
fn describe(error: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in error.chain() {
        let message = cause.to_string();
        if message.is_empty() || text.contains(&message) {
            continue;
        }
        if !text.is_empty() {
            text.push_str(": ");
        }
        text.push_str(&message);
    }
    text
}

/// The exit status of a command, with its error printed once.
fn finish(result: anyhow::Result<()>) -> ExitCode {
    let Err(error) = result else { return ExitCode::SUCCESS };
    if error.chain().any(|cause| cause.is::<out::Closed>()) {
        // The reader of stdout went away (`| head -1`): nothing is wrong.
        return ExitCode::SUCCESS;
    }
    eprintln!("error: {}", describe(&error));
    let timed_out = error.chain().any(|cause| {
        matches!(cause.downcast_ref(), Some(device::servo::RequestError::Timeout { .. }))
            || matches!(cause.downcast_ref(), Some(device::plen2::ReplyError::Timeout { .. }))
    });
    if timed_out {
        eprintln!("hint: a slow link or a busy device may need more time: raise it with --timeout-ms");
    }
    let other_protocol = error.chain().find_map(|cause| {
        if matches!(cause.downcast_ref(), Some(device::servo::RequestError::NotThisProtocol { .. })) {
            Some("plen2 or --protocol rflex")
        } else if matches!(cause.downcast_ref(), Some(device::plen2::ReplyError::NotThisProtocol { .. }))
            || matches!(cause.downcast_ref(), Some(device::plen2::Plen2OpError::Unreadable { .. }))
        {
            Some("servo or --protocol rflex")
        } else {
            None
        }
    });
    if let Some(others) = other_protocol {
        eprintln!("hint: if it is another kind of device, say which: try --protocol {others}");
    }
    match error.chain().find_map(|cause| cause.downcast_ref::<rflex::Exit>()) {
        Some(rflex::Exit(code)) => ExitCode::from(*code),
        None => ExitCode::FAILURE,
    }
}

fn import(port: &PortArgs, input: &std::path::Path, choices: servo::ImportChoices) -> anyhow::Result<()> {
    let project::Loaded { project: loaded, unknown_keys } = plen2::load_input(input)?;
    warn_unknown(input, &unknown_keys);
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

/// Keys a file held that Servo Studio does not know: ignored, said once on stderr.
pub(crate) fn warn_unknown(file: &std::path::Path, keys: &[String]) {
    for key in keys {
        eprintln!("warning: {}: {key}: unknown key, ignored (is it misspelt?)", file.display());
    }
}

/// Opens the editor, with `file` if given; with `demo` and no file, on the sample robot.
pub fn gui(file: Option<PathBuf>, demo: bool, protocol: Option<Family>) -> anyhow::Result<()> {
    let project = match &file {
        // A project file, or the PLEN community's motion.json (one file or a folder).
        Some(path) => {
            let loaded = plen2::load_input(path)?;
            warn_unknown(path, &loaded.unknown_keys);
            Some(loaded.project)
        }
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
    // Ctrl-C or kill in the terminal that started the editor: the base stops, the work is kept.
    let interrupts = signals::listen().ok().map(|interrupts| {
        let (forward, forwarded) = crossbeam_channel::unbounded();
        std::thread::spawn(move || {
            for _ in interrupts {
                let _ = forward.send(());
            }
        });
        forwarded
    });
    let start = servo_studio::ui::Start { project, path, demo, family: protocol, interrupts };
    servo_studio::ui::run(start).map_err(|error| {
        anyhow::anyhow!("cannot open the window: {error}. On Linux, a desktop session (X11 or Wayland) and OpenGL drivers are needed")
    })
}

/// Runs `servo-studio check FILE`: every problem with its location (and, for
/// a folder of motion.json files, its file), going on past a file that
/// cannot be read; exit 1 on any error.
pub fn check(file: &std::path::Path) -> ExitCode {
    let report = if file.is_dir() { check_folder(file) } else { check_file(file) };
    match report {
        Ok((errors, warnings)) => {
            let summary = format!("{}: {errors} error(s), {warnings} warning(s)", file.display());
            if out::line(&summary).is_err() {
                return ExitCode::SUCCESS;
            }
            if errors > 0 { ExitCode::FAILURE } else { ExitCode::SUCCESS }
        }
        Err(error) => finish(Err(error)),
    }
}

/// Prints problems (each after `prefix`); returns (errors, warnings).
fn print_problems<'a>(
    problems: impl IntoIterator<Item = (String, &'a project::Problem)>,
) -> Result<(usize, usize), out::Closed> {
    let (mut errors, mut warnings) = (0, 0);
    for (prefix, problem) in problems {
        match problem.severity {
            Severity::Error => errors += 1,
            Severity::Warning => warnings += 1,
        }
        let text = problem.to_string();
        let line = match text.split_once(": ") {
            Some((severity, rest)) if !prefix.is_empty() => format!("{severity}: {prefix}: {rest}"),
            _ => text,
        };
        out::line(&line)?;
    }
    Ok((errors, warnings))
}

fn unknown_key(path: String) -> project::Problem {
    project::Problem {
        severity: Severity::Warning,
        location: project::Location::Key { path },
        kind: project::ProblemKind::UnknownKey,
    }
}

fn check_file(file: &std::path::Path) -> anyhow::Result<(usize, usize)> {
    let project::Loaded { project, unknown_keys } = plen2::load_input(file)?;
    let mut problems: Vec<project::Problem> = unknown_keys.into_iter().map(unknown_key).collect();
    problems.extend(project::validate(&project));

    Ok(print_problems(problems.iter().map(|problem| (String::new(), problem)))?)
}

fn check_folder(folder: &std::path::Path) -> anyhow::Result<(usize, usize)> {
    let files = project::motion_json::motion_files(folder)?;
    let name = |file: &std::path::Path| file.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let (mut errors, mut warnings) = (0, 0);
    let mut motions = Vec::new();
    let mut slot_files: std::collections::BTreeMap<u8, Vec<String>> = std::collections::BTreeMap::new();
    for file in &files {
        match project::motion_json::read_motion_file(file) {
            Ok((motion, unknown)) => {
                let problems: Vec<project::Problem> = unknown.into_iter().map(unknown_key).collect();
                let (e, w) = print_problems(problems.iter().map(|problem| (name(file), problem)))?;
                (errors, warnings) = (errors + e, warnings + w);
                slot_files.entry(motion.slot).or_default().push(name(file));
                motions.push(motion);
            }
            Err(error) => {
                // Said, and the others still checked.
                out::line(&format!("error: {error}"))?;
                errors += 1;
            }
        }
    }
    let project = Project {
        family: Family::Plen2,
        plen2: project::plen2::Plen2Project { motions, ..Default::default() },
        ..Project::default()
    };
    let problems = project::validate(&project);
    let located = problems.iter().map(|problem| {
        let files = match &problem.location {
            project::Location::Motion { slot, .. } | project::Location::Frame { slot, .. } => {
                slot_files.get(slot).map(|files| files.join(", "))
            }
            _ => None,
        };
        (files.unwrap_or_default(), problem)
    });
    let (e, w) = print_problems(located)?;
    Ok((errors + e, warnings + w))
}
