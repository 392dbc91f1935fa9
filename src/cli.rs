//! The command line: argument parsing and the commands. Errors are handled
//! here, once: printed with what to try, and turned into the exit status.
//! Every number is bounded as it is parsed (`bounds`), an option is refused
//! where it does not apply, and output that cannot be written is never a
//! silent success (`out`). The `servo-studio` binary is `main.rs` calling
//! [`run`]; the module lives in the library so that its unit tests run with
//! the library's.

// Output goes through `cli::out`, which never panics when stdout or stderr fail (clippy.toml names the macros).
#![warn(clippy::disallowed_macros)]

mod bounds;
mod check;
mod convert;
mod dynamixel;
mod failed;
pub(crate) mod family;
mod fit;
mod follow_audio;
mod gui;
mod installed;
mod out;
mod play;
mod plen2;
mod probe;
mod rflex;
mod serve;
mod servo;
mod signals;
pub(crate) mod sim;
mod trajectory;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use crate::device;
use crate::project::rflex::Robot;
use crate::project::{self, Family};
pub use failed::{Advised, Exit, exported, import_failed, interrupted, restore_hint};
use out::say;

/// The version `--version` says: the package's, and the commit it was built from.
pub const VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), " (", env!("SERVO_STUDIO_COMMIT"), ")");

/// Servo Studio: pose robot servos live, author actions and macros, and back up
/// and upload servo controller boards.
#[derive(Debug, Parser)]
#[command(name = "servo-studio", version = VERSION, about, long_about = None)]
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
    Family::from_tag(&text.to_ascii_lowercase()).ok_or_else(|| {
        let tags: Vec<&str> = Family::all().iter().map(|family| family.tag()).collect();
        format!("{text:?} is not a family: use {}", tags.join(", "))
    })
}

/// Where the board is and how to talk to it.
#[derive(Debug, Args)]
pub struct PortArgs {
    /// Serial port (/dev/ttyUSB0, COM3) or tcp://HOST:PORT.
    #[arg(long)]
    pub port: String,
    /// Line rate of a serial port, 300..=4000000 (default: the family's, 115200 for servo boards).
    #[arg(long, allow_hyphen_values = true, value_parser = bounds::baud)]
    pub baud: Option<u32>,
    /// How long the device may take to answer, in milliseconds (1..=600000), on
    /// top of the time the bytes need on the line (default: 1000; 600 for PLEN2).
    #[arg(long, allow_hyphen_values = true, value_parser = bounds::timeout_ms)]
    pub timeout_ms: Option<u64>,
    /// The board's family: servo, plen2 or rflex (default: the project file's, else servo).
    #[arg(long, value_parser = parse_family)]
    pub protocol: Option<Family>,
    /// PLEN2: how uploads are paced — fast, adaptive (the default: widens when
    /// the link shows it is late or bursty) or safe (the official 32 bytes, then 50 ms).
    #[arg(long)]
    pub pacing: Option<device::plen2::PacingMode>,
}

impl PortArgs {
    /// The line rate asked for, or the family's default.
    pub fn baud(&self, family: Family) -> u32 {
        self.baud.unwrap_or_else(|| device::line_settings(family).baud)
    }

    /// The timeout asked for, or the family's default, ms.
    pub fn timeout_ms(&self, family: Family) -> u64 {
        self.timeout_ms.unwrap_or_else(|| family::registered(family).map_or(1000, |entry| entry.timeout_ms))
    }

    /// The PLEN2 pacing asked for, or adaptive.
    pub fn pacing(&self) -> device::plen2::PacingMode {
        self.pacing.unwrap_or_default()
    }

    /// Refuses what was given that does not apply to `family`.
    pub fn applies_to(&self, family: Family) -> anyhow::Result<()> {
        if self.pacing.is_some() && !family::registered(family).is_some_and(|entry| entry.paced) {
            anyhow::bail!("--pacing is for PLEN2 uploads; it does not apply to a {family} board. Nothing was done");
        }
        Ok(())
    }
}

/// The subcommands.
// Parsed once a run and matched at once: the size of its largest variant (a
// simulated link's model among the `sim` arguments) costs nothing.
#[allow(clippy::large_enum_variant)]
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
    /// Print the shell completions for SHELL (bash, zsh, fish, elvish, powershell) — e.g.
    /// `servo-studio completions bash > ~/.local/share/bash-completion/completions/servo-studio`.
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
    },
    /// Write a man page for the command and each subcommand into a folder (what the package installs).
    #[command(hide = true)]
    Man {
        /// The folder.
        #[arg(long)]
        out: PathBuf,
    },
    /// Read a sound (WAV, FLAC, MP3, OGG/Vorbis) and print one JSON object:
    /// `duration_s`, `sample_rate`, `channels`, `onsets_s` (seconds). Exits 1
    /// when it cannot be read.
    AudioInfo {
        /// The sound file.
        sound: PathBuf,
        /// How readily a rise counts as an onset, 0 (only the strongest) to 1 (every rise).
        #[arg(long, default_value_t = 0.5, value_parser = bounds::unit)]
        sensitivity: f32,
    },
    /// Follow a sound's loudness with one servo (--servo N) or PLEN2 joint
    /// (--joint NAME): closed in silence, open at the loudest, fitted into
    /// the board's steps or frames within the tolerance. Servo board: writes
    /// a project with one action per step and macro 1 running them; PLEN2: a
    /// motion.json.
    FollowAudio(follow_audio::FollowArgs),
    /// The connection doctor: which family answers on a port (or on every
    /// port), at which baud, what it says of itself, and how its link delivers.
    /// Sends only requests that change nothing on a servo board, a PLEN2 or an
    /// rFLEX base. Exits 1 when nothing answered.
    Probe {
        /// The port (default: every port this computer sees).
        #[arg(long)]
        port: Option<String>,
        /// Ask every family at this line rate (default: each family's own).
        #[arg(long, allow_hyphen_values = true, value_parser = bounds::baud)]
        baud: Option<u32>,
        /// How long a request may wait for its reply to begin, ms (default 500).
        #[arg(long, allow_hyphen_values = true, value_parser = bounds::timeout_ms)]
        timeout_ms: Option<u64>,
    },
    /// Run an emulated board. Prints the port to connect to on the first line.
    Sim {
        /// The emulator's options.
        #[command(flatten)]
        args: sim::SimArgs,
        /// Which family to emulate: servo, plen2 or rflex.
        #[arg(long, value_parser = parse_family, default_value = "servo")]
        protocol: Family,
    },
    /// Play a show with no window: connect every device (saying which answered), play the
    /// show with its sound (or silent, said) on every board together, each run's start, skew
    /// and end logged; Ctrl-C / SIGTERM stop every device (bases brake) and exit 130 / 143.
    /// The boards must hold the show's content (servo-studio import). docs/show.md
    Play(play::PlayArgs),
    /// Remote control with no window: hold every device of a show connected and take HTTP +
    /// JSON (and OSC with --osc) from cue software and control surfaces — play, stop, pose,
    /// drive (with heartbeats), status as Server-Sent Events. Loopback only unless
    /// --token-file. Ctrl-C / SIGTERM stop every device and exit 130 / 143. docs/remote.md
    Serve(serve::ServeArgs),
    /// Read everything from a board into a project file.
    Export {
        /// The board.
        #[command(flatten)]
        port: PortArgs,
        /// The project file to write.
        #[arg(long)]
        out: PathBuf,
        /// PLEN2: the slots to read, e.g. 0-19,70 (default: all 90).
        #[arg(long, value_parser = bounds::parse_slots)]
        slots: Option<bounds::Slots>,
        /// Replace the output file even when it is read-only.
        #[arg(long)]
        force: bool,
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
        /// Open another tool's file (Maestro settings, .mtn, .mtnx, Blender JSON) in the import window.
        #[arg(long)]
        import: Option<PathBuf>,
        /// Open a show (or a project as a show of one device) in the show window.
        #[arg(long)]
        show: Option<PathBuf>,
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
        /// PLEN2: the motion's slot (0..=89).
        #[arg(long, allow_hyphen_values = true, value_parser = bounds::slot)]
        slot: Option<u8>,
        /// Servo board: the action's id.
        #[arg(long, allow_hyphen_values = true)]
        action: Option<i32>,
        /// Servo board: the macro's id.
        #[arg(long = "macro", allow_hyphen_values = true)]
        macro_id: Option<i32>,
        /// PLEN2: the motion played before (its last frame is where this one starts; default: power-up, all zeros).
        #[arg(long, requires = "slot", allow_hyphen_values = true, value_parser = bounds::slot)]
        from_slot: Option<u8>,
        /// At most this long, above 0 and up to 3600 s (a motion that never ends stops here).
        #[arg(long, default_value_t = 30.0, allow_hyphen_values = true, value_parser = bounds::trajectory_seconds)]
        seconds: f64,
        /// The CSV file to write.
        #[arg(long)]
        out: PathBuf,
        /// Replace the output file even when it is read-only.
        #[arg(long)]
        force: bool,
    },
    /// Convert motions from another tool (Pololu Maestro settings file, RoboPlus
    /// Motion .mtn, R+ Motion .mtnx, Blender servo-animation JSON) into a servo or
    /// PLEN2 project, or a project (or one of those files) into a Maestro
    /// settings file or Blender JSON. Prints what was converted, approximated
    /// and dropped (docs/import-export.md).
    Convert(convert::ConvertArgs),
    /// Fit a recording (the CSV `trajectory` writes: `t_ms`, then a column per
    /// joint or servo by name; PLEN2 values in tenths of a degree relative to
    /// home, servo values in degrees; any sample rate) into the fewest frames
    /// or steps whose playback on the board stays within the tolerance at every
    /// update. PLEN2: writes a motion.json; servo board: a project with one
    /// action per step and macro 1 running them in order.
    Fit {
        /// The CSV recording.
        recording: PathBuf,
        /// The board that plays it: plen2 or servo.
        #[arg(long, value_parser = parse_family)]
        protocol: Family,
        /// How far the board's playback may stray from the recording at any update, degrees.
        #[arg(long, default_value_t = 1.0, allow_hyphen_values = true, value_parser = bounds::tolerance_deg)]
        tolerance_deg: f64,
        /// At most this many frames or steps (PLEN2: 20, what a motion holds).
        #[arg(long, allow_hyphen_values = true, value_parser = bounds::max_frames)]
        max_frames: Option<usize>,
        /// The motion's or macro's name (default: the recording's file name).
        #[arg(long)]
        name: Option<String>,
        /// The file to write.
        #[arg(long)]
        out: PathBuf,
        /// Replace the output file even when it is read-only.
        #[arg(long)]
        force: bool,
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
        CliCommand::Check { file } => return check::run(&file),
        CliCommand::Ports => servo::ports(),
        CliCommand::Completions { shell } => installed::completions(shell),
        CliCommand::Man { out } => installed::man_pages(&out),
        CliCommand::AudioInfo { sound, sensitivity } => audio_info(&sound, sensitivity),
        CliCommand::Probe { port, baud, timeout_ms } => probe::run(port.as_deref(), baud, timeout_ms),
        CliCommand::Sim { args, protocol } => sim::run(&args, protocol),
        CliCommand::Play(args) => play::run(&args),
        CliCommand::Serve(args) => serve::run(&args),
        CliCommand::Rflex { command } => rflex::run(&command),
        CliCommand::Export { port, out, slots, force } => export(&port, &out, slots.as_ref(), force),
        CliCommand::Import { port, input, yes, force, no_backup, backup_dir } => {
            import(&port, &input, family::ImportChoices { yes, force, backup_dir: (!no_backup).then_some(backup_dir) })
        }
        CliCommand::Board { command: BoardCommand::Info { port } } => {
            let family = port.protocol.unwrap_or_default();
            port.applies_to(family)
                .and_then(|()| family::board(family, "board info"))
                .and_then(|board| (board.info)(&port))
        }
        CliCommand::Gui { file, demo, protocol, import, show } => {
            gui::run(file.as_deref(), demo, protocol, (import, show))
        }
        CliCommand::Convert(args) => convert::run_args(args),
        CliCommand::FollowAudio(args) => follow_audio::run(&args).and_then(|said| match out::line(&said) {
            Ok(()) | Err(out::Unwritten::Closed) => Ok(()),
            Err(error) => Err(error.into()),
        }),
        CliCommand::Fit { recording, protocol, tolerance_deg, max_frames, name, out, force } => {
            let request = fit::FitRequest { recording, family: protocol, tolerance_deg, max_frames, name, out, force };
            fit::run(&request).and_then(|fitted| match out::line(&fit::said(&fitted, protocol, &request.out)) {
                Ok(()) | Err(out::Unwritten::Closed) => Ok(()),
                Err(error) => Err(error.into()),
            })
        }
        CliCommand::Trajectory { file, slot, action, macro_id, from_slot, seconds, out, force } => {
            let subject = match (slot, action, macro_id) {
                (Some(slot), _, _) => trajectory::Subject::Slot { slot, from_slot },
                (_, Some(action), _) => trajectory::Subject::Action(action),
                (_, _, Some(id)) => trajectory::Subject::Macro(id),
                // clap requires one of them.
                (None, None, None) => trajectory::Subject::Action(0),
            };
            trajectory::run(&file, subject, seconds, &out, force).and_then(|(rows, covered)| {
                match out::line(&format!("wrote {rows} rows ({covered:.3} s) to {}", out.display())) {
                    // The file is written: a reader gone from stdout changes nothing.
                    Ok(()) | Err(out::Unwritten::Closed) => Ok(()),
                    Err(error) => Err(error.into()),
                }
            })
        }
    };
    finish(result)
}

fn export(port: &PortArgs, out: &std::path::Path, slots: Option<&bounds::Slots>, force: bool) -> anyhow::Result<()> {
    let family = port.protocol.unwrap_or_default();
    port.applies_to(family)?;
    // Refused before the board is read: a FIFO, a device, a folder or (without
    // --force) a read-only file is never replaced.
    writable_output(out, force)?;
    (family::board(family, "export")?.export)(port, out, slots)
}

/// Refuses an output path that must not be replaced: anything but a regular
/// file (a symbolic link is followed), and a read-only file unless `force`.
pub fn writable_output(out: &std::path::Path, force: bool) -> anyhow::Result<()> {
    let target = project::output_path(out)?;
    if !force
        && let Ok(metadata) = std::fs::metadata(&target)
        && metadata.permissions().readonly()
    {
        anyhow::bail!(
            "{} is read-only: it is not replaced unless you say so with --force. Nothing was done",
            target.display()
        );
    }
    Ok(())
}

/// Refuses to write `out` when it is one of `inputs` — by the same name,
/// through a symbolic link, or as another name of the same file (a hard
/// link): checked before anything is read, so an input is never replaced by
/// what was made of it.
pub fn output_not_an_input(out: &std::path::Path, inputs: &[&std::path::Path]) -> anyhow::Result<()> {
    let Ok(written) = std::fs::metadata(out) else { return Ok(()) };
    for input in inputs {
        let Ok(read) = std::fs::metadata(input) else { continue };
        if same_file(&written, &read) {
            anyhow::bail!(
                "{} is {}, which this command reads: write to another file (nothing was read or written)",
                out.display(),
                if out == *input { "an input".to_string() } else { format!("the input {}", input.display()) }
            );
        }
    }
    Ok(())
}

/// Whether two files' metadata are of one file.
#[cfg(unix)]
fn same_file(a: &std::fs::Metadata, b: &std::fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt;
    (a.dev(), a.ino()) == (b.dev(), b.ino())
}

/// Whether two files' metadata are of one file (by what can be compared off Unix).
#[cfg(not(unix))]
fn same_file(a: &std::fs::Metadata, b: &std::fs::Metadata) -> bool {
    a.len() == b.len() && a.modified().ok() == b.modified().ok() && a.created().ok() == b.created().ok()
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
/// `audio-info`: the sound's shape and onsets as one JSON object.
fn audio_info(sound: &std::path::Path, sensitivity: f32) -> anyhow::Result<()> {
    let analysis = crate::audio::analyse(sound, sensitivity, |_| {})?;
    let info = serde_json::json!({
        "duration_s": analysis.duration_s(),
        "sample_rate": analysis.sample_rate,
        "channels": analysis.channels,
        "onsets_s": analysis.onsets_s,
    });
    match out::line(&info.to_string()) {
        Ok(()) | Err(out::Unwritten::Closed) => Ok(()),
        Err(error) => Err(error.into()),
    }
}

fn finish(result: anyhow::Result<()>) -> ExitCode {
    let Err(error) = result else { return ExitCode::SUCCESS };
    if let Some(out::Unwritten::Closed) = error.chain().find_map(|cause| cause.downcast_ref::<out::Unwritten>()) {
        // The reader of stdout went away (`| head -1`) before the output was whole: said by the status alone.
        return ExitCode::from(out::Unwritten::Closed.exit_code());
    }
    say!("error: {}", describe(&error));
    let timed_out = error.chain().any(|cause| {
        matches!(cause.downcast_ref(), Some(device::servo::RequestError::Timeout { .. }))
            || matches!(cause.downcast_ref(), Some(device::plen2::ReplyError::Timeout { .. }))
    });
    if timed_out {
        say!("hint: a slow link or a busy device may need more time: raise it with --timeout-ms");
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
        say!("hint: if it is another kind of device, say which: try --protocol {others}");
    }
    // An `Exit` given as the error itself, as one of its causes, or as a context on top.
    let exit = error.downcast_ref::<Exit>().or_else(|| error.chain().find_map(|cause| cause.downcast_ref::<Exit>()));
    match exit {
        Some(Exit(code)) => ExitCode::from(*code),
        None => ExitCode::FAILURE,
    }
}

fn import(port: &PortArgs, input: &std::path::Path, choices: family::ImportChoices) -> anyhow::Result<()> {
    let loaded = open_input(input)?.loaded;
    warn_unknown(input, &loaded);
    let loaded = loaded.project;
    let family = port.protocol.unwrap_or(loaded.family);
    port.applies_to(family)?;
    if family != loaded.family {
        anyhow::bail!(
            "{} is a {} project but --protocol {family} was given; nothing was written",
            input.display(),
            loaded.family
        );
    }
    (family::board(family, "import")?.import)(port, input, &loaded, choices)
}

/// Opens what a command is given: a project file, a motion.json or a folder
/// of them (only regular files, within the size cap).
pub fn open_input(path: &std::path::Path) -> anyhow::Result<project::input::Opened> {
    Ok(project::input::open(path)?)
}

/// Keys a file held that Servo Studio does not know: ignored, said once on
/// stderr (the first hundred by name, then how many more).
pub(crate) fn warn_unknown(file: &std::path::Path, loaded: &project::Loaded) {
    const NAMED: usize = 100;
    for key in loaded.unknown_keys.iter().take(NAMED) {
        say!("warning: {}: {key}: unknown key, ignored (is it misspelt?)", file.display());
    }
    let more = loaded.unknown_key_count().saturating_sub(NAMED);
    if more > 0 {
        say!("warning: {}: {more} more unknown keys, ignored", file.display());
    }
}

#[cfg(test)]
mod props;
