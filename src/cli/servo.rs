//! The commands that talk to a servo board, and the emulated servo board's runner.

use std::io::{BufRead, IsTerminal, Write};
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::{Context, bail};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};

use super::PortArgs;
use servo_studio::device::Cancel;
use servo_studio::device::servo::{
    self as device, ImportOptions, Phase, Progress, Requester, ServoBoard, ServoImage, SessionConfig,
};
use servo_studio::link::{self, Driver, LinkEvent, PortName, no_waker};
use servo_studio::project::rflex::Robot;
use servo_studio::project::{self, Family, Project};
use servo_studio::sim::{self, Faults, LineNoise, LinkKind, ServoSim, SimConfig};

/// `servo-studio sim` options.
#[derive(Debug, Args)]
pub struct SimArgs {
    /// Serve on a pseudo-terminal (the default on Linux and macOS).
    #[arg(long, conflicts_with = "tcp")]
    pub pty: bool,
    /// Serve on TCP at this address, e.g. 127.0.0.1:5000 (port 0 picks one).
    #[arg(long)]
    pub tcp: Option<SocketAddr>,
    /// Preload the board from this project file.
    #[arg(long)]
    pub state: Option<PathBuf>,
    /// Emulate this line rate (bytes take 10 bits each); default: as fast as the link goes.
    #[arg(long)]
    pub baud: Option<u32>,
    /// Time between a request and its response, in milliseconds.
    #[arg(long, default_value_t = 0)]
    pub turnaround_ms: u64,
    /// The board's memory in bytes.
    #[arg(long, default_value_t = 256 * 1024)]
    pub memory: i32,
    /// Faults to inject (servo board), e.g. garbage-every=3,drop-every=7,disconnect-after=40,refuse-add=42.
    #[arg(long, default_value = "")]
    pub faults: Faults,
    /// Send every frame stuffed (rFLEX base).
    #[arg(long)]
    pub stuffed: bool,
    /// Line noise on the output (rFLEX base), e.g. garbage-every=5,corrupt-every=7,cut-every=11.
    #[arg(long, default_value = "")]
    pub noise: LineNoise,
    /// The robot (rFLEX base): b21r, atrv-jr or magellan.
    #[arg(long, value_parser = super::parse_robot, default_value = "b21r")]
    pub robot: Robot,
    /// The line to the robot (PLEN2): clean, bursty[=MS] (a Bluetooth LE
    /// bridge, 7.5–30 ms connection interval, 15 by default), late=MS (writes
    /// held back up to MS ms) or slow=BAUD.
    #[arg(long, default_value = "clean")]
    pub link: LinkKind,
}

fn session_config(port: &PortArgs) -> SessionConfig {
    SessionConfig {
        response_timeout: Duration::from_millis(port.timeout_ms(Family::Servo)),
        ..SessionConfig::default()
    }
}

fn connect(port: &PortArgs) -> anyhow::Result<ServoBoard> {
    let name = PortName::parse(&port.port)?;
    Ok(ServoBoard::connect(&name, port.baud(Family::Servo), session_config(port), no_waker())?)
}

/// A progress bar on stderr (hidden when stderr is not a terminal).
fn progress_bar() -> (ProgressBar, impl FnMut(&Progress)) {
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("{prefix:>8} [{bar:30}] {pos}/{len} {wide_msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    let shown = bar.clone();
    let update = move |progress: &Progress| {
        shown.set_prefix(match progress.phase {
            Phase::Read => "reading",
            Phase::Write => "writing",
            Phase::Verify => "verifying",
        });
        shown.set_length(u64::try_from(progress.total).unwrap_or(u64::MAX));
        shown.set_position(u64::try_from(progress.done).unwrap_or(u64::MAX));
        shown.set_message(progress.item.to_string());
    };
    (bar, update)
}

pub fn ports() -> anyhow::Result<()> {
    let ports = link::list_ports()?;
    if ports.is_empty() {
        super::out::line("no serial ports found (a board on a network bridge is reached as tcp://HOST:PORT)")?;
    }
    for port in ports {
        super::out::line(&format!("{}\t{}", port.name, port.description))?;
    }
    Ok(())
}

pub fn sim(args: &SimArgs) -> anyhow::Result<()> {
    let image = match &args.state {
        Some(path) => {
            let loaded =
                project::load(path).with_context(|| format!("cannot preload the board from {}", path.display()))?;
            if loaded.family != Family::Servo {
                bail!(
                    "{} is a {} project; the emulated servo board takes a servo project",
                    path.display(),
                    loaded.family
                );
            }
            ServoImage::from_project(&loaded.servo)
                .with_context(|| format!("{} cannot be stored on a board", path.display()))?
        }
        None => ServoImage::default(),
    };
    let config = SimConfig {
        total_memory_bytes: args.memory,
        baud: args.baud,
        turnaround: Duration::from_millis(args.turnaround_ms),
        faults: args.faults.clone(),
        ..SimConfig::default()
    };
    serve(args, ServoSim::new(config, image))
}

/// Serves an emulator of any family on a pseudo-terminal or TCP; prints the port on
/// the first line of stdout, then runs until killed.
pub fn serve<D: Driver>(args: &SimArgs, emulator: D) -> anyhow::Result<()> {
    let handle = match args.tcp {
        Some(address) => sim::spawn_tcp(emulator, address, no_waker())?,
        None => spawn_pty(emulator)?,
    };
    let mut stdout = std::io::stdout();
    writeln!(stdout, "{}", handle.port_name)?;
    stdout.flush()?;
    eprintln!("emulated board ready on {} (Ctrl-C to stop)", handle.port_name);
    for event in handle.events() {
        if let LinkEvent::Disconnected { reason } = event {
            eprintln!("client disconnected: {reason}");
            if args.tcp.is_none() {
                return Ok(());
            }
        }
    }
    Ok(())
}

#[cfg(unix)]
fn spawn_pty<D: Driver>(emulator: D) -> anyhow::Result<sim::SimHandle<D::Command, D::Event>> {
    Ok(sim::spawn_pty(emulator, no_waker())?)
}

#[cfg(not(unix))]
fn spawn_pty<D: Driver>(_emulator: D) -> anyhow::Result<sim::SimHandle<D::Command, D::Event>> {
    bail!("pseudo-terminals exist only on Linux and macOS; use --tcp 127.0.0.1:5000")
}

pub fn export(port: &PortArgs, out: &Path) -> anyhow::Result<()> {
    // Refused before the board is read: a FIFO, a device or a folder is never replaced.
    project::output_path(out)?;
    let board = connect(port)?;
    let (bar, mut update) = progress_bar();
    let exported = device::export(&board.requester(), &mut update, &Cancel::never());
    bar.finish_and_clear();
    let exported =
        exported.with_context(|| format!("export from {} failed; {} was not written", port.port, out.display()))?;
    project::save(out, &Project::servo(exported.clone()))?;
    eprintln!(
        "exported project {} ({} servos, {} actions, {} macros, {} joystick tables) to {}",
        exported.project_id,
        exported.servos.len(),
        exported.actions.len(),
        exported.macros.len(),
        exported.joystick_tables.len(),
        out.display()
    );
    Ok(())
}

pub fn confirm(port: &str, input: &Path, backup: bool) -> anyhow::Result<()> {
    let stdin = std::io::stdin();
    if !stdin.is_terminal() {
        bail!(
            "refusing to overwrite the board on {port} without confirmation (standard input is not a terminal); pass --yes"
        );
    }
    eprint!(
        "This erases everything on the board on {port} and writes {}.{} Type yes to continue: ",
        input.display(),
        if backup { " A backup of the board is saved first." } else { " No backup is saved (--no-backup)." }
    );
    let mut answer = String::new();
    stdin.lock().read_line(&mut answer)?;
    if answer.trim() != "yes" {
        bail!("not confirmed; the board is unchanged");
    }
    Ok(())
}

/// How `import` runs.
#[derive(Debug)]
pub struct ImportChoices {
    /// Do not ask.
    pub yes: bool,
    /// Write even when validation finds errors.
    pub force: bool,
    /// Where the backup goes; `None` = no backup.
    pub backup_dir: Option<PathBuf>,
}

pub fn import(port: &PortArgs, input: &Path, loaded: &Project, choices: ImportChoices) -> anyhow::Result<()> {
    let ImportChoices { yes, force, backup_dir } = choices;
    // Refuse before connecting and before asking: nothing is written either way.
    let problems: Vec<project::Problem> =
        project::validate_servo(&loaded.servo).into_iter().filter(|p| p.severity == project::Severity::Error).collect();
    if !problems.is_empty() && !force {
        return Err(device::OpError::Invalid { problems })
            .with_context(|| format!("{} was not imported into {}", input.display(), port.port));
    }
    let board = connect(port)?;
    if !yes {
        confirm(&port.port, input, backup_dir.is_some())?;
    }
    let options = ImportOptions { backup_dir, verify: true, force };
    let (bar, mut update) = progress_bar();
    let requester: Requester = board.requester();
    let report = device::import(&requester, &loaded.servo, &options, &mut update, &Cancel::never());
    bar.finish_and_clear();
    let report = report.map_err(|failure| {
        let advice = super::restore_hint("", &port.port, failure.backup.as_deref(), &failure.left);
        anyhow::Error::new(super::Advised { error: *failure, advice }).context(format!(
            "import of {} into {} failed",
            input.display(),
            port.port
        ))
    })?;
    if let Some(backup) = &report.backup {
        eprintln!("backup of the previous contents: {}", backup.display());
    }
    eprintln!("wrote {} item(s) to {} and verified them", report.written, port.port);
    Ok(())
}

pub fn info(port: &PortArgs) -> anyhow::Result<()> {
    let board = connect(port)?;
    let info = device::board_info(&board.requester())?;
    let print = |text: String| super::out::line(&text);
    print(format!("project id: {}", info.project_id))?;
    match info.total_bytes {
        Some(total) => print(format!("memory: {} of {total} bytes free", info.free_bytes))?,
        None => print(format!("memory: {} bytes free", info.free_bytes))?,
    }
    print(format!("battery: {}", device::battery_text(info.battery_permil)))?;
    print(format!("servos: {}", info.servos.len()))?;
    for servo in &info.servos {
        print(format!(
            "  servo {:>3}: angle {:>5}  current {:>5}  temperature {:>5}  type {}  {}  {}",
            servo.servo_id,
            servo.angle,
            servo.current_adc,
            servo.temperature_adc,
            servo.servo_type,
            if servo.is_start { "running" } else { "stopped" },
            if servo.is_hold { "holding" } else { "released" },
        ))?;
    }
    Ok(())
}
